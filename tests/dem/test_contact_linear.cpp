// Analytic two-particle tests of the linear contact law, shear rotation, Coulomb limit and
// local damping (vem-void-expansion-method §2.1, doh-elastic-properties §2.1).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "packlab/core/random.hpp"
#include "packlab/dem/contact/linear.hpp"
#include "packlab/dem/engine.hpp"
#include "packlab/dem/local_damping.hpp"
#include "head_on_collision.hpp"

using namespace packlab;
using namespace packlab::dem;

namespace {

using test::Collision;
using test::collide;
using test::head_on_pair;

}  // namespace

TEST(LinearContact, HeadOnCollisionDurationAndRestitution) {
  const double r = 0.25e-6, rho = 3690, kn = 1000;
  const double m = rho * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const double m_eff = m / 2;
  for (auto rule : {StiffnessRule::contact, StiffnessRule::particle}) {
    EngineConfig config;
    config.types = {Material{kn, 0.0, 0.0, rho, 0.0}};
    config.stiffness_rule = rule;
    const double k_contact = rule == StiffnessRule::contact ? kn : kn / 2;
    const double expected = std::numbers::pi * std::sqrt(m_eff / k_contact);
    const double dt = expected / 2000;
    const Collision c = collide(head_on_pair(r, 1e-3, 1e-3 * r), config, dt);
    // The contact is resolved to one step at each end.
    EXPECT_NEAR(c.duration, expected, 2 * dt) << stiffness_rule_name(rule);
    EXPECT_NEAR(c.restitution, 1.0, 1e-5) << stiffness_rule_name(rule);
  }
}

TEST(LinearContact, LocalDampingRestitutionMatchesAnalyticValue) {
  // Cundall damping scales the force by (1+alpha) while decelerating and (1-alpha) while
  // accelerating, so the linear spring gives e = sqrt((1-alpha)/(1+alpha)) exactly.
  const double r = 1e-3, rho = 2500, kn = 1e4;
  const double m = rho * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  for (double alpha : {0.1, 0.3, 0.7}) {
    EngineConfig config;
    config.types = {Material{kn, 0.0, 0.0, rho, alpha}};
    config.stiffness_rule = StiffnessRule::contact;
    const double dt = std::numbers::pi * std::sqrt(m / 2 / kn) / 4000;
    const Collision c = collide(head_on_pair(r, 0.01, 1e-6), config, dt);
    EXPECT_NEAR(c.restitution, std::sqrt((1 - alpha) / (1 + alpha)), 2e-3) << "alpha " << alpha;
  }
}

TEST(LocalDamping, NoForceNoDampingAndOpposesVelocity) {
  // Steady motion (zero unbalanced force) is not damped at all, unlike viscous damping.
  const Vec3 zero_force = apply_local_damping({0, 0, 0}, {3, -2, 1}, 0.7);
  EXPECT_EQ(zero_force, (Vec3{0, 0, 0}));
  // The damping force always opposes the velocity, per component, with magnitude alpha |F|.
  const Vec3 f{2, -4, 1}, v{1, 1, -1};
  const Vec3 damped = apply_local_damping(f, v, 0.5);
  const Vec3 fd = damped - f;
  EXPECT_DOUBLE_EQ(fd.x, -1.0);  // -0.5*|2|*sign(1)
  EXPECT_DOUBLE_EQ(fd.y, -2.0);  // -0.5*|-4|*sign(1)
  EXPECT_DOUBLE_EQ(fd.z, 0.5);   // -0.5*|1|*sign(-1)
  for (int a = 0; a < 3; ++a) EXPECT_LE(fd[a] * v[a], 0.0);
}

TEST(LocalDamping, FreeParticleKeepsItsVelocity) {
  Packing p;
  p.box.length = {10, 10, 10};
  p.add({5, 5, 5}, 0.5);
  p.velocity = {{0.1, -0.2, 0.3}};
  EngineConfig config;
  config.types = {Material{100, 10, 0.5, 1000, 0.9}};
  Engine engine(p, config);
  engine.run(1000);
  EXPECT_EQ(engine.packing().velocity[0], (Vec3{0.1, -0.2, 0.3}));
}

TEST(LinearContact, ShearSpringBuildsUpToTheCoulombLimit) {
  LinearContact::Params params{1000.0, 100.0, 0.5};
  ContactGeometry g;
  g.normal = {1, 0, 0};
  g.overlap = 1e-3;
  g.branch_i = g.branch_j = 1.0;
  g.relative_velocity = {0, 1e-3, 0};  // j slides along +y
  g.mean_spin = {0, 0, 0};
  g.dt = 0.01;
  Vec3 history{};
  const double fn = 1000.0 * 1e-3;  // 1 N
  for (int s = 1; s <= 1000; ++s) {
    const PairForce f = LinearContact::evaluate(g, params, history);
    const double elastic = 100.0 * 1e-3 * 0.01 * s;  // k_s * accumulated displacement
    EXPECT_NEAR(f.force_on_j.y, -std::min(elastic, 0.5 * fn), 1e-12) << "step " << s;
    EXPECT_DOUBLE_EQ(f.force_on_j.x, fn);
    // Torques of the shear force about both centres, same sense (rolling couple).
    EXPECT_NEAR(f.torque_i.z, f.torque_j.z, 1e-15);
  }
  EXPECT_NEAR(norm(history), 0.5 * fn, 1e-12);  // sliding at the limit
}

TEST(LinearContact, ShearForceRotatesWithTheContactPlane) {
  LinearContact::Params params{1000.0, 100.0, 10.0};
  ContactGeometry g;
  g.overlap = 1e-3;
  g.branch_i = g.branch_j = 1.0;
  g.relative_velocity = {0, 0, 0};
  g.mean_spin = {0, 0, 0};
  g.dt = 0.01;
  // Tilt: the pair turned by a small angle about z; the stored shear force (normal was x)
  // turns into the new plane; its magnitude changes at second order in the angle only.
  const double tilt = 1e-4;
  Vec3 history{0, 0.3, 0.4};
  g.normal = {std::cos(tilt), std::sin(tilt), 0};
  const PairForce f = LinearContact::evaluate(g, params, history);
  EXPECT_NEAR(dot(history, g.normal), 0.0, 1e-15);
  EXPECT_NEAR(norm(history), 0.5, 0.5 * tilt * tilt);
  EXPECT_NEAR(dot(f.force_on_j, g.normal), 1.0, 1e-12);
  // Twist: spinning about the normal turns the shear force about it by omega dt.
  Vec3 twisted{0, 0.5, 0};
  g.normal = {1, 0, 0};
  g.mean_spin = {2.0, 0, 0};  // rad/s
  LinearContact::evaluate(g, params, twisted);
  // First-order rotation: the angle is atan(omega dt), the magnitude grows by 1 + O(angle^2).
  EXPECT_NEAR(std::atan2(twisted.z, twisted.y), std::atan(2.0 * 0.01), 1e-12);
  EXPECT_NEAR(norm(twisted), 0.5, 0.5 * 4e-4);
}

TEST(LinearContact, StrainEnergyIsTheWorkOfTheForce) {
  // F_n = -dE/d(overlap): check numerically.
  LinearContact::Params params{750.0, 0.0, 0.0};
  ContactGeometry g{{0, 0, 1}, 2e-3, 1, 1, {0, 0, 0}, {0, 0, 0}, 1e-3};
  Vec3 h{};
  const double h_step = 1e-7;
  ContactGeometry plus = g, minus = g;
  plus.overlap += h_step;
  minus.overlap -= h_step;
  const double dE = (LinearContact::evaluate(plus, params, h).energy - LinearContact::evaluate(minus, params, h).energy) /
                    (2 * h_step);
  EXPECT_NEAR(dE, LinearContact::evaluate(g, params, h).normal_force, 1e-9);
}

// Without friction the engine evaluates the law's central form (no history, spins or
// velocities gathered): it must give the numbers of the full law, whose shear force is then
// scaled to its zero Coulomb limit. Random geometries, velocities, spins and stale histories.
TEST(LinearContact, WithoutFrictionTheCentralFormGivesTheFullLawsNumbers) {
  Random rng(11);
  for (int k = 0; k < 2000; ++k) {
    const LinearContact::Params params{rng.uniform(1.0, 1e4), rng.uniform(0.0, 1e3), 0.0};
    ASSERT_TRUE(LinearContact::torque_free(params));
    ContactGeometry g{};
    g.normal = rng.unit_vector();
    g.radius_i = rng.uniform(0.5, 2.0);
    g.radius_j = rng.uniform(0.5, 2.0);
    g.overlap = rng.uniform(0.0, 0.1) * (g.radius_i + g.radius_j);
    g.branch_i = g.radius_i - 0.5 * g.overlap;
    g.branch_j = g.radius_j - 0.5 * g.overlap;
    g.relative_velocity = rng.uniform(0.0, 10.0) * rng.unit_vector();
    g.mean_spin = rng.uniform(0.0, 10.0) * rng.unit_vector();
    g.dt = rng.uniform(1e-4, 1e-2);
    Vec3 history = rng.uniform(0.0, 1.0) * rng.unit_vector();
    const PairForce full = LinearContact::evaluate(g, params, history);
    const PairForce central = LinearContact::evaluate_central(g, params);
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(central.force_on_j[a], full.force_on_j[a]) << k;
      EXPECT_EQ(central.torque_i[a], 0.0);
      EXPECT_EQ(central.torque_j[a], 0.0);
      EXPECT_EQ(full.torque_i[a], 0.0) << k;
    }
    EXPECT_EQ(central.energy, full.energy) << k;
    EXPECT_EQ(central.normal_force, full.normal_force) << k;
    EXPECT_EQ(central.stiffness, full.stiffness) << k;
    EXPECT_EQ(norm(history), 0.0) << k;  // the full law's spring: gone
  }
}
