// Engine records of elastic bonds: current axial strain per bond, the failure log (time and
// position), breakage exactly at sigma_max under a steady pull, removal after the relaxation.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "packlab/dem/bond/elastic_bond.hpp"
#include "packlab/dem/engine.hpp"

using namespace packlab;
using namespace packlab::dem;

namespace {
constexpr double r = 7.5e-9, l0 = 2 * r;
constexpr double E = 6.53e9, nu = 0.17, sigma_max = 94.3e6;
constexpr double inf = std::numeric_limits<double>::infinity();

// Particle 0 fixed, particle 1 moving away along x at 1 m/s, bonded at its rest length.
Packing pulled_pair() {
  Packing p;
  p.box.length = {20 * r, 10 * r, 10 * r};
  p.box.periodic = {false, false, false};
  p.add({4 * r, 5 * r, 5 * r}, r);
  p.add({4 * r + l0, 5 * r, 5 * r}, r);
  p.fixed = {1, 0};
  p.density = {1297.0, 1e12};
  p.velocity = {Vec3{}, Vec3{1.0, 0, 0}};
  p.bonds.add(0, 1, {0, 0, 0}, 0, l0);
  return p;
}

// One elastic bond material (silica), steps of 1 ps, one thread.
EngineConfig elastic_bond_config() {
  EngineConfig c;
  c.types = {Material{}};
  c.bond_materials = BondMaterialList<ElasticBond>{{E, nu, sigma_max, inf, 1.0, 1e-9}};
  c.threads = 1;
  c.time_step = 1e-12;
  return c;
}
}  // namespace

TEST(BondRecords, PulledBondFailsAtSigmaMaxAndIsLoggedAtItsMidpoint) {
  // Particle 0 fixed, particle 1 pulled along x at a constant 1 m/s (a huge density makes the
  // bond force negligible for its motion). Normal stress E (L - L0) / L0 reaches sigma_max at
  // strain sigma_max / E, i.e. at t* = L0 sigma_max / (E v); the failure is logged within one
  // step of t*, at the bond's midpoint; the bond is removed one relaxation time later.
  const Packing p = pulled_pair();
  EngineConfig c = elastic_bond_config();
  c.contact_law = "hertz_mindlin";
  c.types[0].youngs_modulus = E;
  c.types[0].poisson_ratio = nu;
  c.types[0].damping = 0.0;
  Engine e(p, c);
  const double t_fail = l0 * sigma_max / (E * 1.0);
  e.run(static_cast<long>(0.5 * t_fail / 1e-12));
  {
    const std::vector<double> s = e.bond_strains();
    ASSERT_EQ(s.size(), 1u);
    const Packing now = e.packing();
    const double expected = (now.position[1].x - now.position[0].x - l0) / l0;
    EXPECT_NEAR(s[0], expected, 1e-9 * expected);
    EXPECT_NEAR(s[0], 0.5 * sigma_max / E, 0.01 * sigma_max / E);
    EXPECT_TRUE(e.bond_breaks().empty());
  }
  e.run(static_cast<long>(0.6 * t_fail / 1e-12));
  ASSERT_EQ(e.bond_breaks().size(), 1u);
  const BondBreak& b = e.bond_breaks()[0];
  EXPECT_EQ(b.bond, 0u);
  EXPECT_NEAR(b.time, t_fail, 1.5e-12);
  const double x_mid = 4 * r + 0.5 * (l0 + 1.0 * b.time);
  EXPECT_NEAR(b.position.x, x_mid, 1e-3 * r);
  EXPECT_NEAR(b.position.y, 5 * r, 1e-9 * r);
  EXPECT_TRUE(std::isnan(e.bond_strains()[0]));  // failed bonds have no strain
  EXPECT_EQ(e.intact_bonds(), 1u);               // still relaxing
  Diagnostics d = e.step_measured();
  EXPECT_EQ(d.broken_bonds, 1u);
  e.run(static_cast<long>(1e-9 / 1e-12) + 2);
  EXPECT_EQ(e.intact_bonds(), 0u);
  EXPECT_EQ(e.bond_breaks().size(), 1u);
}

TEST(BondRecords, BreakLogSurvivesACheckpoint) {
  const Packing p = pulled_pair();
  const EngineConfig c = elastic_bond_config();
  Engine a(p, c);
  a.run(400);
  ASSERT_EQ(a.bond_breaks().size(), 1u);
  std::stringstream state;
  a.save_state(state);
  Engine b(p, c);
  b.load_state(state);
  ASSERT_EQ(b.bond_breaks().size(), 1u);
  EXPECT_EQ(b.bond_breaks()[0].time, a.bond_breaks()[0].time);
  EXPECT_EQ(b.bond_breaks()[0].position.x, a.bond_breaks()[0].position.x);
}

TEST(BondRecords, NormalCriterionBreaksCompressedBondsOnlyWhenAsked) {
  // A bond shortened to a normal stress of 1.5 sigma_max: intact by default (MUSEN's default,
  // eq. 16 for stretched bonds), failed with compressive_breakage; stretched: failed either way.
  ContactGeometry g{};
  g.normal = {1, 0, 0};
  g.radius_i = g.radius_j = r;
  g.rest_length = l0;
  g.dt = 1e-12;
  const double strain = 1.5 * sigma_max / E;
  for (bool compressive : {false, true})
    for (double sign : {-1.0, 1.0}) {
      ElasticBond::Params p{E, nu, sigma_max, inf, 1.0, 1e-9};
      p.compressive_breakage = compressive;
      g.overlap = -sign * strain * l0;
      g.branch_i = g.branch_j = r - 0.5 * g.overlap;
      ElasticBond::State s;
      const BondForce f = ElasticBond::evaluate(g, p, s);
      EXPECT_EQ(f.failed, compressive || sign > 0) << "compressive_breakage " << compressive << " sign " << sign;
    }
}

TEST(BondRecords, BondsAreNamedByTheirInputIndexWhateverOrderTheEngineKeepsThemIn) {
  // Three pulled pairs along x, at different heights and speeds, their bonds listed neither in
  // the particles' order nor in space's (the engine keeps bonds by owner, in its own particle
  // order). Strains, breaks and packing() name each bond by its index in the input list, and a
  // checkpoint taken between two breaks continues bit for bit.
  Packing p;
  p.box.length = {40 * r, 30 * r, 10 * r};
  p.box.periodic = {false, false, false};
  const double speed[3] = {2.0, 1.0, 0.5};  // pairs A, B, C
  const double height[3] = {25 * r, 15 * r, 5 * r};
  // Input particles: moving B, fixed C, fixed A, moving C, moving A, fixed B.
  const int moving[3] = {4, 0, 3}, fixed[3] = {2, 5, 1};
  p.position.resize(6);
  p.velocity.assign(6, Vec3{});
  p.fixed.assign(6, 0);
  p.density.assign(6, 1e12);
  for (int k = 0; k < 3; ++k) {
    p.position[fixed[k]] = {4 * r, height[k], 5 * r};
    p.position[moving[k]] = {4 * r + l0, height[k], 5 * r};
    p.velocity[moving[k]] = {speed[k], 0, 0};
    p.fixed[fixed[k]] = 1;
  }
  p.radius.assign(6, r);
  p.type.assign(6, 0);
  p.bonds.add(moving[2], fixed[2], {0, 0, 0}, 0, l0);  // bond 0: pair C, breaks last
  p.bonds.add(fixed[0], moving[0], {0, 0, 0}, 0, l0);  // bond 1: pair A, breaks first
  p.bonds.add(moving[1], fixed[1], {0, 0, 0}, 0, l0);  // bond 2: pair B
  const EngineConfig c = elastic_bond_config();
  Engine e(p, c);
  const double t_fail = l0 * sigma_max / E;  // at 1 m/s
  e.run(static_cast<long>(0.4 * t_fail / 1e-12));
  const std::vector<double> strain = e.bond_strains();
  const Packing now = e.packing();
  ASSERT_EQ(strain.size(), 3u);
  for (std::size_t b = 0; b < 3; ++b) {
    const double length = norm(now.position[now.bonds.j[b]] - now.position[now.bonds.i[b]]);
    EXPECT_DOUBLE_EQ(strain[b], (length - l0) / l0) << "bond " << b;
  }
  EXPECT_EQ(now.bonds.i, p.bonds.i);
  EXPECT_EQ(now.bonds.j, p.bonds.j);
  // Pair A (2 m/s) has failed by 0.6 t*, pair B (1 m/s) by 1.1 t*, pair C (0.5 m/s) by 2.1 t*.
  e.run(static_cast<long>(0.2 * t_fail / 1e-12));
  ASSERT_EQ(e.bond_breaks().size(), 1u);
  EXPECT_EQ(e.bond_breaks()[0].bond, 1u);
  EXPECT_NEAR(e.bond_breaks()[0].position.y, height[0], 1e-9 * r);
  EXPECT_TRUE(std::isnan(e.bond_strains()[1]));
  EXPECT_FALSE(std::isnan(e.bond_strains()[0]));
  EXPECT_FALSE(std::isnan(e.bond_strains()[2]));
  std::stringstream state;
  e.save_state(state);
  Engine resumed(p, c);
  resumed.load_state(state);
  const long rest = static_cast<long>(1.5 * t_fail / 1e-12);
  e.run(rest);
  resumed.run(rest);
  ASSERT_EQ(e.bond_breaks().size(), 3u);
  EXPECT_EQ(e.bond_breaks()[1].bond, 2u);
  EXPECT_EQ(e.bond_breaks()[2].bond, 0u);
  EXPECT_NEAR(e.bond_breaks()[1].time, t_fail, 1.5e-12);
  EXPECT_NEAR(e.bond_breaks()[2].time, 2 * t_fail, 1.5e-12);
  EXPECT_NEAR(e.bond_breaks()[2].position.y, height[2], 1e-9 * r);
  // Each break at the bond's midpoint at the step it failed, before the particles moved on
  // (they move in the same parallel region: dem/step.cpp): one step later it would lie
  // v dt / 2 = 2.5e-13 to 1e-12 m (3e-5 to 1.3e-4 r) further along x.
  const double pair_speed[3] = {speed[2], speed[0], speed[1]};  // by bond index
  for (const BondBreak& b : e.bond_breaks())
    EXPECT_NEAR(b.position.x, 4 * r + 0.5 * (l0 + pair_speed[b.bond] * b.time), 1e-6 * r) << "bond " << b.bond;
  ASSERT_EQ(resumed.bond_breaks().size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(resumed.bond_breaks()[k].bond, e.bond_breaks()[k].bond);
    EXPECT_EQ(resumed.bond_breaks()[k].time, e.bond_breaks()[k].time);
  }
  EXPECT_EQ(resumed.packing().position, e.packing().position);
}
