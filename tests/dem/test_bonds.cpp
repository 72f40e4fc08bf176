// PFC contact bonds (doh-elastic-properties §2.1): tension, breakage, periodic images.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "packlab/core/error.hpp"
#include "packlab/dem/engine.hpp"

using namespace packlab;
using namespace packlab::dem;

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// Two spheres of radius 0.5 along x, bonded, centre distance 1 + gap, in a box of edge L.
Packing bonded_pair(double gap, Vec3 box = {10, 10, 10}, std::array<bool, 3> periodic = {false, false, false}) {
  Packing p;
  p.box.length = box;
  p.box.periodic = periodic;
  p.add({2.0, 2, 2}, 0.5);
  p.add({3.0 + gap, 2, 2}, 0.5);
  p.bonds.add(0, 1, {0, 0, 0}, 0, 1.0 + gap);
  return p;
}

EngineConfig bond_config(double normal_strength, double shear_strength, double damping = 0.0) {
  EngineConfig c;
  c.types = {Material{1000.0, 100.0, 0.5, 1000.0, damping}};
  c.stiffness_rule = StiffnessRule::contact;
  c.bond_materials = BondMaterialList<ContactBond>{{800.0, 80.0, normal_strength, shear_strength}};
  c.threads = 1;
  return c;
}

double mass_of(double r, double rho) { return rho * 4.0 / 3.0 * std::numbers::pi * r * r * r; }

}  // namespace

TEST(ContactBond, PullsSeparatedParticlesWithTheContactStiffness) {
  // Gap 0.01: the bond continues the linear law into tension, F_n = k_n U_n, U_n = -0.01.
  Packing p = bonded_pair(0.01);
  EngineConfig c = bond_config(inf, inf);
  c.time_step = 1e-4;
  Engine e(p, c);
  e.run(1);
  const Packing out = e.packing();
  const double m = mass_of(0.5, 1000.0);
  // After one step v = F/m dt, F = 800 * 0.01 N towards each other.
  EXPECT_NEAR(out.velocity[1].x, -800.0 * 0.01 / m * 1e-4, 1e-15);
  EXPECT_NEAR(out.velocity[0].x, 800.0 * 0.01 / m * 1e-4, 1e-15);
  EXPECT_EQ(e.intact_bonds(), 1u);
}

TEST(ContactBond, OscillatesAboutTouchingAndConservesEnergyWithoutDamping) {
  Packing p = bonded_pair(0.02);
  EngineConfig c = bond_config(inf, inf);
  c.time_step_safety = 0.02;
  Engine e(p, c);
  Diagnostics d = e.step_measured();
  const double e0 = d.kinetic_energy + d.strain_energy;
  EXPECT_NEAR(d.strain_energy, 0.5 * 800.0 * 0.02 * 0.02, 1e-3 * e0);
  double worst = 0.0, max_gap = 0.0, min_gap = 1.0;
  for (int k = 0; k < 2000; ++k) {
    e.run(4);
    d = e.step_measured();
    worst = std::max(worst, std::abs(d.kinetic_energy + d.strain_energy - e0) / e0);
    const Packing out = e.packing();
    const double gap = out.position[1].x - out.position[0].x - 1.0;
    max_gap = std::max(max_gap, gap);
    min_gap = std::min(min_gap, gap);
  }
  EXPECT_LT(worst, 1e-3);
  // Symmetric oscillation about touching, from 0.02 apart to 0.02 overlap: while bonded the
  // bond law replaces the contact law in compression too (one spring, as PFC's contact bond).
  EXPECT_NEAR(max_gap, 0.02, 1e-4);
  EXPECT_NEAR(min_gap, -0.02, 1e-4);
}

TEST(ContactBond, BreaksInTensionAboveTheNormalStrengthAndThenActsAsAContact) {
  // Pulled apart at 2 mm/s each (kinetic energy 2.1e-3 J > bond energy at failure 6.3e-4 J):
  // the tension k_n U_n exceeds F_nB = 1 N at U_n = -1/800 m.
  Packing p = bonded_pair(0.0);
  p.velocity = {{-0.002, 0, 0}, {0.002, 0, 0}};
  EngineConfig c = bond_config(1.0, inf);
  c.time_step_safety = 0.02;
  Engine e(p, c);
  double gap_at_break = -1;
  for (int k = 0; k < 100000 && e.intact_bonds() == 1; ++k) {
    e.run(1);
    const Packing out = e.packing();
    gap_at_break = out.position[1].x - out.position[0].x - 1.0;
  }
  ASSERT_EQ(e.intact_bonds(), 0u);
  // Broke within a step of reaching the strength (relative motion 6e-5 m per step).
  EXPECT_NEAR(gap_at_break, 1.0 / 800.0, 1e-4);
  const Diagnostics d = e.step_measured();
  EXPECT_EQ(d.broken_bonds, 1u);
  EXPECT_EQ(d.contacts, 0u);  // apart: no contact, no bond
  EXPECT_EQ(e.packing().bonds.state[0], 1);
}

TEST(ContactBond, BreaksInShearAboveTheShearStrength) {
  Packing p = bonded_pair(0.0);
  p.velocity = {{0, -0.01, 0}, {0, 0.01, 0}};
  EngineConfig c = bond_config(inf, 0.05);
  Engine e(p, c);
  for (int k = 0; k < 200000 && e.intact_bonds() == 1; ++k) e.run(1);
  EXPECT_EQ(e.intact_bonds(), 0u);
}

TEST(ContactBond, SurvivesPeriodicWrapsAndKeepsItsImage) {
  // A touching bonded pair straddling the x boundary drifts through the box several times:
  // no force may appear (the bond rests at touching) and the written image stays right.
  Packing p;
  p.box.length = {4, 4, 4};
  p.add({3.7, 2, 2}, 0.5);
  p.add({0.7, 2, 2}, 0.5);  // 1.0 from particle 0 through the boundary
  p.bonds.add(0, 1, {1, 0, 0}, 0, 1.0);
  p.velocity = {{0.5, 0.1, 0}, {0.5, 0.1, 0}};
  EngineConfig c = bond_config(1e-9, 1e-9);  // any spurious force would break it
  Engine e(p, c);
  const long steps = static_cast<long>(20.0 / e.time_step());  // 10 m of drift along x
  e.run(steps);
  ASSERT_EQ(e.intact_bonds(), 1u);
  const Packing out = e.packing();
  const Vec3 bond = out.position[1] + out.box.shift_vector(out.bonds.image[0]) - out.position[0];
  EXPECT_NEAR(norm(bond), 1.0, 1e-9);
  EXPECT_NEAR(bond.x, 1.0, 1e-9);
  EXPECT_GT(e.neighbor_builds(), 1);
}

TEST(ContactBond, CheckpointWithBondsContinuesBitwise) {
  Packing p = bonded_pair(0.015, {3, 10, 10}, {true, false, false});
  p.velocity = {{0.1, 0.02, 0}, {-0.05, 0, 0.01}};
  const EngineConfig c = bond_config(inf, inf);
  Engine straight(p, c);
  straight.run(600);
  Engine first(p, c);
  first.run(300);
  std::stringstream state;
  first.save_state(state);
  Engine resumed(p, c);
  resumed.load_state(state);
  resumed.run(300);
  EXPECT_TRUE(resumed.particles().position == straight.particles().position);
  EXPECT_TRUE(resumed.particles().velocity == straight.particles().velocity);
}

TEST(ContactBond, BondsWithoutParametersAreAnInputError) {
  Packing p = bonded_pair(0.0);
  EngineConfig c = bond_config(inf, inf);
  c.bond_materials = BondMaterialList<ContactBond>{};
  EXPECT_THROW(Engine(p, c), InputError);
  c = bond_config(inf, inf);
  std::get<BondMaterialList<ContactBond>>(c.bond_materials)[0].normal_stiffness = -1;
  EXPECT_THROW(Engine(p, c), InputError);
}
