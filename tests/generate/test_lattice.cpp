#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "packlab/analyze/coordination.hpp"
#include "packlab/generate/lattice.hpp"

using namespace packlab;

TEST(Lattice, VolumeFractionAndCoordinationOfTouchingLattices) {
  struct Expect {
    const char* type;
    double phi;
    double cn;
    int per_cell;
  };
  const double pi = std::numbers::pi;
  for (const Expect e : {Expect{"sc", pi / 6, 6, 1}, Expect{"bcc", pi * std::sqrt(3.0) / 8, 8, 2},
                         Expect{"fcc", pi / (3 * std::sqrt(2.0)), 12, 4}}) {
    generate::LatticeParams p;
    p.type = generate::lattice_type_from_name(e.type);
    p.cells = {3, 4, 5};
    p.radius = 0.25e-6;
    const Packing packing = generate::make_lattice(p);
    EXPECT_EQ(packing.size(), static_cast<std::size_t>(60 * e.per_cell)) << e.type;
    EXPECT_NEAR(packing.volume_fraction(), e.phi, 1e-12) << e.type;
    analyze::Coordination cn(0.01);
    cn.compute(packing);
    EXPECT_DOUBLE_EQ(cn.mean(), e.cn) << e.type;
    for (int c : cn.counts()) ASSERT_EQ(c, e.cn) << e.type;
  }
}

TEST(Lattice, SmallestPeriodicBoxesStillCountEveryNeighbour) {
  // Two SC cells per axis (edge 2 diameters) and one FCC cell (edge 1.41 diameters): images
  // of the same particle are neighbours several times over.
  generate::LatticeParams p;
  p.type = generate::LatticeType::sc;
  p.cells = {2, 2, 2};
  Packing one = generate::make_lattice(p);
  analyze::Coordination cn(0.01);
  cn.compute(one);
  EXPECT_DOUBLE_EQ(cn.mean(), 6.0);
  p.type = generate::LatticeType::fcc;
  p.cells = {1, 1, 1};
  cn.compute(generate::make_lattice(p));
  EXPECT_DOUBLE_EQ(cn.mean(), 12.0);
}

TEST(Lattice, GapSeparatesNeighbours) {
  generate::LatticeParams p;
  p.type = generate::LatticeType::fcc;
  p.cells = {2, 2, 2};
  p.radius = 1.0;
  p.gap = 0.05;  // 2.5 % of a diameter: beyond eps = 0.01, inside eps = 0.03
  const Packing packing = generate::make_lattice(p);
  analyze::Coordination tight(0.01), loose(0.03);
  tight.compute(packing);
  loose.compute(packing);
  EXPECT_DOUBLE_EQ(tight.mean(), 0.0);
  EXPECT_DOUBLE_EQ(loose.mean(), 12.0);
}

TEST(Coordination, ReadingBeforeComputingIsAnError) {
  analyze::Coordination cn;
  EXPECT_THROW((void)cn.mean(), std::logic_error);
}
