#include <gtest/gtest.h>

#include <cmath>

#include "packlab/core/error.hpp"
#include "packlab/generate/bonding.hpp"
#include "packlab/generate/lattice.hpp"

using namespace packlab;
using namespace packlab::generate;

namespace {

// Every bond's stored image and rest length reproduce its centre distance.
void expect_consistent(const Packing& p) {
  for (std::size_t b = 0; b < p.bonds.size(); ++b) {
    const auto& img = p.bonds.image[b];
    const Vec3 shift{img[0] * p.box.length.x, img[1] * p.box.length.y, img[2] * p.box.length.z};
    const Vec3 d = p.position[p.bonds.j[b]] + shift - p.position[p.bonds.i[b]];
    ASSERT_NEAR(norm(d), p.bonds.rest_length[b], 1e-12 * p.bonds.rest_length[b]);
  }
}

}  // namespace

TEST(Bonding, ContactModelOnFccBondsTheTwelveNeighbours) {
  LatticeParams lp;
  lp.cells = {3, 3, 3};
  Packing p = make_lattice(lp);
  BondingOptions options;
  options.cutoff_ratio = bonding_cutoff_ratio("contact", 0.01, 1.75);
  add_bonds(p, options);
  EXPECT_EQ(p.bonds.size(), 6 * p.size());  // 12 per particle, each bond shared
  expect_consistent(p);
  for (double l : p.bonds.rest_length) EXPECT_NEAR(l, 1.0, 1e-12);
}

TEST(Bonding, BeamCutoffOnFccReachesTheThirdShell) {
  // Shells of FCC at d, sqrt(2) d, sqrt(3) d, 2 d with 12, 6, 24, 12 members: 1.75 d takes
  // the first three (42 neighbours), 1.4 d the first only.
  LatticeParams lp;
  lp.cells = {4, 4, 4};
  Packing p = make_lattice(lp);
  BondingOptions options;
  options.cutoff_ratio = bonding_cutoff_ratio("elastic", 0.01, 1.75);
  add_bonds(p, options);
  EXPECT_EQ(p.bonds.size(), 21 * p.size());
  expect_consistent(p);
  options.cutoff_ratio = 1.4;
  add_bonds(p, options);
  EXPECT_EQ(p.bonds.size(), 6 * p.size());
}

TEST(Bonding, MaterialRuleFromTypesAndNoBondMarker) {
  LatticeParams lp;
  lp.cells = {2, 2, 2};
  Packing p = make_lattice(lp);
  for (std::size_t k = 0; k < p.size(); k += 2) p.type[k] = 3;
  BondingOptions options;
  options.material_of_types = [](int a, int b) { return a == 3 && b == 3 ? -1 : (a == 3 || b == 3 ? 1 : 0); };
  add_bonds(p, options);
  ASSERT_FALSE(p.bonds.empty());
  for (std::size_t b = 0; b < p.bonds.size(); ++b) {
    const int ti = p.type[p.bonds.i[b]], tj = p.type[p.bonds.j[b]];
    EXPECT_FALSE(ti == 3 && tj == 3);
    EXPECT_EQ(p.bonds.material[b], ti == 3 || tj == 3 ? 1 : 0);
  }
}

TEST(Bonding, BadModelAndCutoffAreInputErrors) {
  EXPECT_THROW(bonding_cutoff_ratio("glue", 0.01, 1.75), InputError);
  EXPECT_THROW(bonding_cutoff_ratio("elastic", 0.01, 2.5), InputError);
  EXPECT_THROW(bonding_cutoff_ratio("contact", -0.1, 1.75), InputError);
}
