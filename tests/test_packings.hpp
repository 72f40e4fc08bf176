// Packings that several test files build: lattices of touching spheres, bare or bonded.
#pragma once

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "packlab/core/packing.hpp"
#include "packlab/core/random.hpp"
#include "packlab/generate/bonding.hpp"
#include "packlab/generate/fba.hpp"
#include "packlab/generate/lattice.hpp"

namespace packlab::test {

// An empty packing in an open (not periodic) cube [0, edge]^3, to place a few spheres in.
inline Packing open_cube(double edge) {
  Packing p;
  p.box.length = {edge, edge, edge};
  p.box.periodic = {false, false, false};
  return p;
}

// A `type` lattice of touching spheres of `radius`, `cells` unit cells along x, y and z.
inline Packing lattice(generate::LatticeType type, std::array<int, 3> cells, double radius = 0.5) {
  generate::LatticeParams lp;
  lp.type = type;
  lp.cells = cells;
  lp.radius = radius;
  return generate::make_lattice(lp);
}

// FCC, `cells` unit cells along each axis, radius 0.5 (neighbour distance 1).
inline Packing fcc(int cells) { return lattice(generate::LatticeType::fcc, {cells, cells, cells}); }

// The lattice above with a bond between every pair closer than cutoff_ratio (r_i + r_j).
inline Packing bonded_lattice(generate::LatticeType type, std::array<int, 3> cells, double radius,
                              double cutoff_ratio) {
  Packing p = lattice(type, cells, radius);
  generate::BondingOptions bo;
  bo.cutoff_ratio = cutoff_ratio;
  generate::add_bonds(p, bo);
  return p;
}

// A pore-free force-biased packing of n spheres of `radius` (porosity 0.38, periodic x, y, box
// 1.5 times as high as wide), elastic bonds to 1.75 d: the opal paper's bulk sample, small.
inline Packing random_bonded_sample(long n, unsigned seed, double radius) {
  const double d = 2 * radius;
  Box box;
  box.periodic = {true, true, false};
  const double a = std::cbrt(static_cast<double>(n) * std::numbers::pi / 6 * d * d * d / 0.62 / 1.5);
  box.length = {a, a, 1.5 * a};
  generate::FbaParams fp;
  fp.target_porosity = 0.38;
  Random rng(seed);
  const std::vector<double> radii = generate::fba_class_radii(n, generate::SizeClasses{}, rng);
  Packing p = generate::fba_pack(box, radii, fp, rng).packing;
  generate::BondingOptions bo;
  bo.cutoff_ratio = 1.75;
  generate::add_bonds(p, bo);
  return p;
}

}  // namespace packlab::test
