// The linear adhesive (DMT-type) contact law against what is known exactly: its force curve,
// the pull-off force 2 pi W R*, the equilibrium overlap F_0 / k_n, energy conservation of an
// undamped pair, attraction across the gap (the neighbour list covers the law's reach), and
// the registry around it (validation of the properties it reads, the checkpoint's law tag).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "packlab/core/error.hpp"
#include "packlab/dem/contact/linear_adhesive.hpp"
#include "packlab/dem/engine.hpp"

using namespace packlab;
using namespace packlab::dem;

namespace {

constexpr double radius = 1e-6, density = 2500.0, kn = 10.0, work = 0.05, range = 0.1e-6;

Material adhesive_material(double damping) {
  Material m;
  m.normal_stiffness = kn;
  m.shear_stiffness = 0.5 * kn;
  m.friction = 0.3;
  m.density = density;
  m.damping = damping;
  m.work_of_adhesion = work;
  m.adhesion_range = range;
  return m;
}

EngineConfig adhesive_config(double damping) {
  EngineConfig c;
  c.contact_law = "linear_adhesive";
  c.types = {adhesive_material(damping)};
  c.stiffness_rule = StiffnessRule::contact;  // the pair's stiffness is k_n itself
  c.threads = 1;
  return c;
}

// Two equal spheres on the x axis, centres `distance` apart, in a large open box.
Packing pair(double distance) {
  Packing p;
  p.box.lo = {-20 * radius, -20 * radius, -20 * radius};
  p.box.length = {40 * radius, 40 * radius, 40 * radius};
  p.box.periodic = {false, false, false};
  p.add({-0.5 * distance, 0, 0}, radius);
  p.add({0.5 * distance, 0, 0}, radius);
  return p;
}

double pull_off() { return 2.0 * std::numbers::pi * work * 0.5 * radius; }  // R* = r / 2

ContactGeometry head_on(double overlap) {
  ContactGeometry g{};
  g.normal = {1, 0, 0};
  g.overlap = overlap;
  g.radius_i = g.radius_j = radius;
  g.branch_i = g.branch_j = radius - 0.5 * overlap;
  g.dt = 1e-9;
  return g;
}

}  // namespace

TEST(LinearAdhesive, ForceCurveMatchesTheLawPiecewise) {
  const auto p = LinearAdhesive::mix(adhesive_material(0), adhesive_material(0), StiffnessRule::contact);
  const double f0 = pull_off();
  EXPECT_NEAR(LinearAdhesive::pull_off_force(p, radius, radius), f0, 1e-15 * f0);
  for (double d : {0.02e-6, 0.005e-6, 0.0, -0.25 * range, -0.5 * range, -0.9 * range, -range, -2 * range}) {
    Vec3 history{};
    const PairForce f = LinearAdhesive::evaluate(head_on(d), p, history);
    const double expected = d >= 0 ? kn * d - f0 : -f0 * std::max(0.0, 1.0 + d / range);
    EXPECT_NEAR(f.normal_force, expected, 1e-12 * f0) << "overlap " << d;
    EXPECT_NEAR(f.force_on_j.x, expected, 1e-12 * f0);
  }
  EXPECT_DOUBLE_EQ(LinearAdhesive::reach(p), range);
}

TEST(LinearAdhesive, PullOffForceOfAPairPulledApartIsTwoPiWRStar) {
  // Both particles fixed and driven apart at a slow constant speed: the largest tension read
  // from the contact forces is the DMT pull-off force, reached as the pair separates.
  const double f0 = pull_off();
  Packing p = pair(2 * radius - 0.5 * f0 / kn);
  p.fixed = {1, 1};
  EngineConfig c = adhesive_config(0.0);
  const double speed = 1e-3;
  c.time_step = 1e-3 * f0 / kn / speed;  // 1e-3 of the adhesive overlap per step
  Engine engine(p, c);
  engine.particles().velocity[0] = {0, 0, 0};
  engine.particles().velocity[1] = {0, 0, 0};
  for (std::size_t k = 0; k < 2; ++k)
    if (engine.original_index()[k] == 1) engine.particles().velocity[k] = {speed, 0, 0};
  double largest_tension = 0.0, last_force = 1.0;
  for (int s = 0; s < 8000; ++s) {
    engine.run(1);
    const ContactForces forces = engine.contact_forces();
    last_force = forces.size() ? forces.force[0].x * (forces.i[0] == 0 ? 1.0 : -1.0) : 0.0;
    largest_tension = std::max(largest_tension, -last_force);
  }
  EXPECT_NEAR(largest_tension, f0, 2e-3 * f0);
  EXPECT_EQ(last_force, 0.0);  // beyond the range: no force, no listed interaction
}

TEST(LinearAdhesive, DampedPairSettlesAtTheEquilibriumOverlap) {
  const double f0 = pull_off();
  Engine engine(pair(2 * radius + 0.5 * range), adhesive_config(0.7));
  for (int s = 0; s < 200; ++s) engine.run(100);
  const auto x = engine.packing().position;
  const double overlap = 2 * radius - (x[1].x - x[0].x);
  EXPECT_NEAR(overlap, f0 / kn, 1e-6 * f0 / kn);
}

TEST(LinearAdhesive, UndampedPairConservesEnergyAcrossAttractionAndContact) {
  // Released at rest inside the range: the pair is pulled together, bounces on the repulsive
  // spring and oscillates in the well. Kinetic + interaction energy is conserved.
  EngineConfig c = adhesive_config(0.0);
  Engine engine(pair(2 * radius + 0.8 * range), c);
  engine.set_time_step(0.01 * engine.time_step());
  const Diagnostics first = engine.step_measured();
  const double e0 = first.kinetic_energy + first.strain_energy;
  ASSERT_LT(e0, 0.0);  // bound: the attraction's energy is negative
  double worst = 0.0, deepest = 0.0;
  for (int s = 0; s < 40000; ++s) {
    const Diagnostics d = engine.step_measured();
    worst = std::max(worst, std::abs(d.kinetic_energy + d.strain_energy - e0));
    deepest = std::min(deepest, d.strain_energy);
  }
  const double well = 0.5 * pull_off() * range;  // depth of the well at touching
  EXPECT_LT(deepest, -well);                      // it went into contact
  EXPECT_LT(worst, 1e-3 * well);
}

TEST(LinearAdhesive, AttractsAcrossAGapWiderThanTheSkin) {
  // The Verlet skin is far smaller than the gap: the pair is listed because the law declares
  // its reach, so the attraction acts from the first step.
  EngineConfig c = adhesive_config(0.0);
  c.skin_ratio = 0.001;
  Engine engine(pair(2 * radius + 0.5 * range), c);
  engine.run(1);
  const auto v = engine.packing().velocity;
  EXPECT_GT(v[0].x, 0.0);
  EXPECT_LT(v[1].x, 0.0);
  Engine beyond(pair(2 * radius + 1.01 * range), c);
  beyond.run(1);
  EXPECT_EQ(beyond.packing().velocity[0].x, 0.0);
}

TEST(LinearAdhesive, RegistryValidatesTheLawsOwnProperties) {
  EXPECT_NE(std::find(contact_law_names().begin(), contact_law_names().end(), std::string("linear_adhesive")),
            contact_law_names().end());
  EngineConfig c = adhesive_config(0.0);
  c.types[0].adhesion_range = 0.0;
  try {
    Engine engine(pair(3 * radius), c);
    FAIL() << "adhesion_range = 0 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("adhesion_range"), std::string::npos) << e.what();
  }
  // The linear law does not read adhesion_range: the same material is valid for it.
  c.contact_law = "linear";
  EXPECT_NO_THROW(Engine(pair(3 * radius), c));
}

TEST(LinearAdhesive, CheckpointIsTaggedWithTheLawsName) {
  EngineConfig c = adhesive_config(0.0);
  Engine adhesive(pair(2 * radius + 0.5 * range), c);
  adhesive.run(10);
  std::stringstream state;
  adhesive.save_state(state);
  c.contact_law = "linear";
  Engine linear(pair(2 * radius + 0.5 * range), c);
  try {
    linear.load_state(state);
    FAIL() << "a linear_adhesive checkpoint was loaded into a linear engine";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("linear_adhesive"), std::string::npos) << e.what();
  }
}
