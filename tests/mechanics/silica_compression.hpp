// The uniaxial compression set-up that several mechanics tests share: the opal paper's silica
// particles and elastic bonds (mechanics/opal_materials.hpp) with the given bond values, one
// thread.
#pragma once

#include "packlab/mechanics/opal_materials.hpp"
#include "packlab/mechanics/uniaxial_compression.hpp"

namespace packlab::test {

inline mechanics::UniaxialCompressionOptions silica_compression_options(double youngs_modulus, double poisson_ratio,
                                                                        double strength) {
  mechanics::OpalMaterials m;
  m.silica_youngs_modulus = youngs_modulus;
  m.silica_poisson_ratio = poisson_ratio;
  m.silica_strength = strength;
  mechanics::UniaxialCompressionOptions o;
  o.types = mechanics::opal_particle_types(m);
  o.bond_materials = mechanics::opal_bond_materials(m);
  o.threads = 1;
  return o;
}

}  // namespace packlab::test
