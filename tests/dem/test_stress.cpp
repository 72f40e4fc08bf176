// Per-particle Cauchy stress (bpm-inverse-opals eq. 21) on configurations with known answers.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "packlab/dem/engine.hpp"
#include "packlab/generate/lattice.hpp"

using namespace packlab;
using namespace packlab::dem;

TEST(ParticleStress, CompressedSimpleCubicLatticeIsIsotropicAndMatchesTheContactForce) {
  // SC lattice, spacing 1, radii 0.505 (overlap 0.01): six contacts of force k * 0.01 along
  // the axes. sigma_xx = 1/(2V) * 2 contacts * (l = 1) * (-F) = -F / V, off-diagonals 0.
  generate::LatticeParams lp;
  lp.type = generate::LatticeType::sc;
  lp.cells = {3, 3, 3};
  Packing p = generate::make_lattice(lp);
  for (auto& r : p.radius) r = 0.505;
  EngineConfig c;
  c.types = {Material{1000.0, 100.0, 0.0, 1000.0, 0.7}};
  c.stiffness_rule = StiffnessRule::contact;
  Engine e(p, c);
  const ContactForces forces = e.contact_forces();
  EXPECT_EQ(forces.size(), 3 * p.size());
  const auto stress = particle_stress(forces, p);
  const double volume = 4.0 / 3.0 * std::numbers::pi * std::pow(0.505, 3);
  const double force = 1000.0 * 0.01;
  for (const auto& s : stress) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        EXPECT_NEAR(s[3 * a + b], a == b ? -force / volume : 0.0, 1e-9 * force / volume);
  }
}

TEST(ParticleStress, WallContactsCountWithTheirBranchToTheContactPoint) {
  // A sphere pressed between floor and ceiling (overlap 0.01 each, force 10 N): each wall
  // contact contributes l_z F_z / V with l the vector to its contact point (length 0.49) and
  // F the force on the particle, both compressive: sigma_zz = 2 (-0.49 * 10) / V.
  Packing p;
  p.box.length = {10, 10, 10};
  p.box.periodic = {true, true, false};
  p.add({5, 5, 1.49}, 0.5);
  EngineConfig c;
  c.types = {Material{1000.0, 100.0, 0.0, 1000.0, 0.7}};
  c.stiffness_rule = StiffnessRule::contact;
  Engine e(p, c);
  e.add_wall(Wall{{0, 0, 1.0}, {0, 0, 1}, {}});
  e.add_wall(Wall{{0, 0, 1.98}, {0, 0, -1}, {}});
  const auto stress = particle_stress(e.contact_forces(), p);
  const double volume = 4.0 / 3.0 * std::numbers::pi * 0.125;
  const double expected = 2 * (-0.49 * 10.0) / volume;
  EXPECT_NEAR(stress[0][8], expected, 1e-9 * std::abs(expected));
  EXPECT_NEAR(stress[0][0], 0.0, 1e-12);
}
