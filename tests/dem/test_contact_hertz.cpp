// Hertz-Mindlin (bpm-inverse-opals eq. 5-10) against Hertz theory.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "packlab/core/error.hpp"
#include "packlab/dem/contact/hertz_mindlin.hpp"
#include "packlab/dem/engine.hpp"

using namespace packlab;
using namespace packlab::dem;

namespace {

Material silica(double restitution) {
  Material t;
  t.youngs_modulus = 70e9;
  t.poisson_ratio = 0.17;
  t.density = 2200;
  t.restitution = restitution;
  t.friction = 0.3;
  t.damping = 0.0;
  return t;
}

ContactGeometry at_rest(double overlap, double radius) {
  ContactGeometry g{};
  g.normal = {1, 0, 0};
  g.overlap = overlap;
  g.branch_i = g.branch_j = radius - 0.5 * overlap;
  g.radius_i = g.radius_j = radius;
  g.effective_mass = 1e-15;
  g.dt = 1e-12;
  return g;
}

struct Collision {
  double duration, restitution;
};

Collision collide(double restitution, double speed) {
  const double r = 0.5e-6;
  Packing p;
  p.box.lo = {-10 * r, -10 * r, -10 * r};
  p.box.length = {20 * r, 20 * r, 20 * r};
  p.box.periodic = {false, false, false};
  p.add({-r - 1e-13, 0, 0}, r);  // starts (almost) touching: no steps spent approaching
  p.add({r + 1e-13, 0, 0}, r);
  p.velocity = {{speed, 0, 0}, {-speed, 0, 0}};
  EngineConfig c;
  c.contact_law = "hertz_mindlin";
  c.types = {silica(restitution)};
  c.threads = 1;
  c.time_step = 2e-13;
  Engine e(p, c);
  long in_contact = 0;
  bool touched = false;
  for (long s = 0; s < 10'000'000; ++s) {
    const auto x = e.packing().position;
    if (x[1].x - x[0].x < 2 * r) {
      touched = true;
      ++in_contact;
    } else if (touched) {
      break;
    }
    e.run(1);
  }
  const auto v = e.packing().velocity;
  return {static_cast<double>(in_contact) * c.time_step, (v[1].x - v[0].x) / (2 * speed)};
}

}  // namespace

TEST(HertzMindlin, NormalForceIsHertzAndTheWorkOfItsEnergy) {
  const auto p = HertzMindlin::mix(silica(1), silica(1), StiffnessRule::particle);
  const double e_star = 70e9 / (2 * (1 - 0.17 * 0.17));
  EXPECT_NEAR(p.effective_youngs_modulus, e_star, 1e-6 * e_star);
  const double r = 0.5e-6, r_eff = r / 2;
  for (double xi : {1e-10, 1e-9, 5e-9}) {
    Vec3 h{};
    const PairForce f = HertzMindlin::evaluate(at_rest(xi, r), p, h);
    EXPECT_NEAR(f.normal_force, 4.0 / 3.0 * e_star * std::sqrt(r_eff) * std::pow(xi, 1.5), 1e-12 * f.normal_force);
    Vec3 h1{}, h2{};
    const double dxi = 1e-4 * xi;
    const double de = (HertzMindlin::evaluate(at_rest(xi + dxi, r), p, h1).energy -
                       HertzMindlin::evaluate(at_rest(xi - dxi, r), p, h2).energy) /
                      (2 * dxi);
    EXPECT_NEAR(de, f.normal_force, 1e-6 * f.normal_force);
  }
}

TEST(HertzMindlin, ElasticCollisionLastsTheHertzContactTime) {
  // Hertz: t_c = 2.868 (m*^2 / (R* E*^2 v))^(1/5), v the approach speed; restitution 1.
  const double speed = 0.05;
  const Collision c = collide(1.0, speed);
  const double r = 0.5e-6, m = 2200 * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const double e_star = 70e9 / (2 * (1 - 0.17 * 0.17));
  const double expected = 2.868 * std::pow((m / 2) * (m / 2) / ((r / 2) * e_star * e_star * 2 * speed), 0.2);
  EXPECT_NEAR(c.duration, expected, 2e-3 * expected);
  EXPECT_NEAR(c.restitution, 1.0, 1e-6);
}

TEST(HertzMindlin, DampedRestitutionIsIndependentOfImpactSpeed) {
  // What is exact for this damping (eq. 5, 7): the restitution does not depend on the impact
  // speed (the damping scales with xi^1/4 like the Hertz stiffness), and it grows with e.
  // The realized value is not e itself (the coefficient comes from the linear-spring
  // solution, and the normal force may not pull): measured 0.397 for e = 0.3, 0.550 for
  // e = 0.5 (docs/engine.md).
  double previous = 0.0;
  for (double e : {0.3, 0.5, 0.8}) {
    const Collision slow = collide(e, 0.01);
    const Collision fast = collide(e, 0.1);
    EXPECT_NEAR(slow.restitution, fast.restitution, 1e-3 * slow.restitution) << "e " << e;
    EXPECT_GT(slow.restitution, previous) << "e " << e;
    EXPECT_LT(slow.restitution, 1.0);
    RecordProperty("restitution_for_e_" + std::to_string(e), std::to_string(slow.restitution));
    previous = slow.restitution;
  }
}

TEST(HertzMindlin, TangentialForceSlipsAtTheFrictionLimit) {
  const auto p = HertzMindlin::mix(silica(1), silica(1), StiffnessRule::particle);
  ContactGeometry g = at_rest(2e-9, 0.5e-6);
  g.relative_velocity = {0, 1e-3, 0};
  g.effective_mass = 0.0;  // no damping term: the elastic part alone
  g.dt = 1e-9;             // 1 nm of sliding per step
  Vec3 xi{};
  double previous = 0;
  for (int s = 0; s < 1000; ++s) {
    const PairForce f = HertzMindlin::evaluate(g, p, xi);
    const double ft = std::abs(f.force_on_j.y);
    EXPECT_LE(ft, 0.3 * f.normal_force * (1 + 1e-12));
    EXPECT_GE(ft, previous * (1 - 1e-12));
    previous = ft;
  }
  EXPECT_NEAR(previous, 0.3 * HertzMindlin::evaluate(g, p, xi).normal_force, 1e-9 * previous);
}

TEST(HertzMindlin, RequiresElasticConstants) {
  Packing p;
  p.box.length = {1, 1, 1};
  p.add({0.5, 0.5, 0.5}, 0.1);
  EngineConfig c;
  c.contact_law = "hertz_mindlin";
  c.types = {Material{}};  // youngs_modulus 0
  EXPECT_THROW(Engine(p, c), InputError);
}
