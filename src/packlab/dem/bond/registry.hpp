// The registered bond laws: one line each (see dem/contact/registry.hpp for the contact laws).
#pragma once

#include "packlab/dem/bond/contact_bond.hpp"
#include "packlab/dem/bond/elastic_bond.hpp"
#include "packlab/dem/contact/registry.hpp"

namespace packlab::dem {

using BondLaws = LawList<ContactBond, ElasticBond>;

}  // namespace packlab::dem
