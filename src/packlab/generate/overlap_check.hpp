// The independent overlap check of generated packings (LS, shaking, FBA).
#pragma once

#include "packlab/core/packing.hpp"

namespace packlab::generate {

// Smallest d_ij / (r_i + r_j) over all pairs (periodic images included), by the core
// neighbour list: the independent overlap check. 1 when no pair is within contact range.
double min_contact_ratio(const Packing& packing);

}  // namespace packlab::generate
