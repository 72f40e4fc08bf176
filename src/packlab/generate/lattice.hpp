// Cubic lattices (SC, BCC, FCC) of equal spheres in a periodic box that matches the lattice:
// exact reference structures for tests (known volume fraction and coordination).
#pragma once

#include <array>
#include <string>

#include "packlab/core/packing.hpp"

namespace packlab::generate {

enum class LatticeType { sc, bcc, fcc };

LatticeType lattice_type_from_name(const std::string& name);
std::string lattice_type_name(LatticeType type);

struct LatticeParams {
  LatticeType type = LatticeType::fcc;
  std::array<int, 3> cells{4, 4, 4};  // unit cells per axis
  double radius = 0.5;                // [m]
  double gap = 0.0;                   // surface gap between nearest neighbours [m]; 0 = touching
};

// Nearest-neighbour centre distance 2r + gap sets the cubic lattice constant:
// sc a = d, bcc a = 2d / sqrt(3), fcc a = sqrt(2) d.
double lattice_constant(const LatticeParams& params);

Packing make_lattice(const LatticeParams& params);

}  // namespace packlab::generate
