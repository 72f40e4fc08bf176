// Bonded models from packings: a bond between every pair of particles whose centre distance
// is below cutoff_ratio * (r_i + r_j), across periodic boundaries, with the periodic image and
// the initial (rest) length stored so every later stage reads them from the file.
//   contact model (doh-elastic-properties §2.1): cutoff_ratio = 1 + eps, eps = 0.01, i.e. the
//     pairs that touch within the coordination tolerance;
//   elastic model (the elastic beam bonds of bpm-inverse-opals §2.1, bond law "elastic"): cutoff
//     1.75 d for equal particles, cutoff_ratio 1.75.
// The material of each bond comes from its two particles' types (a rule callback; default 0).
#pragma once

#include <functional>
#include <string>

#include "packlab/core/packing.hpp"

namespace packlab::generate {

struct BondingOptions {
  // A pair is bonded when |r_j + image L - r_i| < cutoff_ratio (r_i + r_j); in [1, 2).
  double cutoff_ratio = 1.01;
  // Material of the bond between particles of types (type_i, type_j); return -1 for "no bond".
  // Empty: material 0 for every pair.
  std::function<int(int, int)> material_of_types;
  int threads = 1;
};

// Cutoff ratio of the named model (named like the bond laws of dem/bond/): "contact" ->
// 1 + eps, "elastic" -> elastic_cutoff (InputError for an
// unknown model naming the allowed ones).
double bonding_cutoff_ratio(const std::string& model, double eps, double elastic_cutoff);

// Replaces packing.bonds by the bonds of `options` (each pair once, i < j, or i == j for a
// particle bonded to its own periodic image). Deterministic and ordered by (i, j).
void add_bonds(Packing& packing, const BondingOptions& options);

}  // namespace packlab::generate
