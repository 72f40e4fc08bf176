// PFC contact bond in shear (doh-elastic-properties §2.1), the parts tests/dem/test_bonds.cpp
// does not cover: the incremental shear spring F_s = k_s U_s under prescribed motion, friction
// superseded while bonded (and back once broken), the same bond across a periodic boundary,
// and the §2.2 relaxation with velocities zeroed after each step (dem/relax.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "packlab/dem/engine.hpp"
#include "packlab/dem/relax.hpp"

using namespace packlab;
using namespace packlab::dem;

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double kn = 800.0, ks = 80.0;

// Two spheres of radius 0.5 touching along x at (x0, 2, 2), (x0 + 1, 2, 2); both fixed, so the
// test prescribes their motion. Box of edge 10, periodic along x when asked.
Packing fixed_pair(double x0, bool periodic, double gap = 0.0, int image_x = 0) {
  Packing p;
  p.box.length = {10, 10, 10};
  p.box.periodic = {periodic, false, false};
  p.add({x0, 2, 2}, 0.5);
  p.add({x0 + 1.0 + gap - 10.0 * image_x, 2, 2}, 0.5);
  p.fixed = {1, 1};
  p.bonds.add(0, 1, {image_x, 0, 0}, 0, 1.0 + gap);
  return p;
}

EngineConfig config(double friction, double normal_strength, double shear_strength, double shear_stiffness = ks) {
  EngineConfig c;
  c.types = {Material{kn, shear_stiffness, friction, 1000.0, 0.0}};
  c.stiffness_rule = StiffnessRule::contact;
  c.bond_materials = BondMaterialList<ContactBond>{{kn, shear_stiffness, normal_strength, shear_strength}};
  c.time_step = 1e-3;
  c.threads = 1;
  return c;
}

// The force on particle 1 split along the current centre line: normal (> 0 pushes 1 away from
// 0, < 0 pulls it back) and the magnitude of the shear part.
struct Split {
  Vec3 force;
  double normal = 0.0, shear = 0.0;
};

// Moves particle 1 along y with speed v for `steps` steps; returns the bond (or contact) force on 1.
Split shear_and_measure(Engine& e, double v, long steps) {
  for (std::size_t k = 0; k < e.particle_count(); ++k)
    e.particles().velocity[k] = e.original_index()[k] == 1 ? Vec3{0, v, 0} : Vec3{};
  e.run(steps);
  const ContactForces f = e.contact_forces();
  Split out;
  for (std::size_t c = 0; c < f.size(); ++c) {
    const double sign = f.j[c] == 1 ? 1.0 : -1.0;  // force on 1; the branch points from i to j
    const Vec3 n = sign * f.branch[c] * (1.0 / norm(f.branch[c]));
    const Vec3 on_1 = sign * f.force[c];
    out.force += on_1;
    out.normal += dot(on_1, n);
    out.shear += norm(on_1 - dot(on_1, n) * n);
  }
  return out;
}

}  // namespace

TEST(ContactBondShear, ShearForceIsTheShearStiffnessTimesTheTangentialDisplacement) {
  Packing p = fixed_pair(4.0, false);
  Engine e(p, config(0.0, inf, inf));
  const double v = 1e-3;  // 1e-6 per step, 200 steps: U_s = 2e-4
  const Split f = shear_and_measure(e, v, 200);
  EXPECT_NEAR(f.force.y, -ks * 2e-4, 1e-6 * ks * 2e-4);
  EXPECT_NEAR(f.shear, ks * 2e-4, 1e-6 * ks * 2e-4);
  // Touching: the normal force and the turn of the shear force are of second order in U_s.
  EXPECT_LT(std::abs(f.force.x), kn * 2e-4 * 2e-4);
  EXPECT_EQ(e.intact_bonds(), 1u);
}

TEST(ContactBondShear, FrictionIsSupersededWhileBondedAndActsAgainOnceBroken) {
  // Overlap 0.01, k_n = 800: normal force 8; friction 0.5 would cap the shear force at 4 under
  // the contact law; the bond does not. k_s = 8000, shear strength 6: breaks after U_s = 7.5e-4.
  const double stiff = 8000.0;
  Packing p = fixed_pair(4.0, false, -0.01);
  Engine e(p, config(0.5, inf, 6.0, stiff));
  const Split f1 = shear_and_measure(e, 1e-2, 60);  // U_s = 6e-4: 4.8 > mu F_n = 4, < 6
  EXPECT_NEAR(f1.shear, stiff * 6e-4, 1e-5 * stiff * 6e-4);
  EXPECT_NEAR(f1.normal, kn * 0.01, 1e-3 * kn * 0.01);
  EXPECT_GT(f1.shear, 1.15 * 0.5 * f1.normal);  // beyond the Coulomb limit: friction superseded
  EXPECT_EQ(e.intact_bonds(), 1u);
  const Split f2 = shear_and_measure(e, 1e-2, 130);  // passes U_s = 7.5e-4: breaks, then slides
  EXPECT_EQ(e.intact_bonds(), 0u);
  // The contact law with Coulomb friction is back: sliding at |F_s| = mu F_n (overlap ~0.01).
  EXPECT_NEAR(f2.normal, kn * 0.01, 1e-3 * kn * 0.01);
  EXPECT_NEAR(f2.shear, 0.5 * f2.normal, 1e-9 * f2.normal);
}

TEST(ContactBondShear, BondAcrossThePeriodicBoundaryActsLikeAnInteriorOne) {
  // The pair straddles x = 0: particle 1 is stored at x0 + 1 - 10 with image +1.
  Packing inside = fixed_pair(4.0, true, 0.02);
  Packing across = fixed_pair(9.6, true, 0.02, 1);
  Engine a(inside, config(0.0, inf, inf));
  Engine b(across, config(0.0, inf, inf));
  const Split fa = shear_and_measure(a, 1e-3, 300);
  const Split fb = shear_and_measure(b, 1e-3, 300);
  EXPECT_NEAR(fa.force.x, fb.force.x, 1e-9 * std::abs(fa.force.x));
  EXPECT_NEAR(fa.force.y, fb.force.y, 1e-9 * std::abs(fa.force.y));
  // Tension F_n = k_n U_n pulls 1 back; U_n from the sheared geometry.
  const double stretch = std::sqrt(1.02 * 1.02 + 3e-4 * 3e-4) - 1.0;
  EXPECT_NEAR(fa.normal, -kn * stretch, 1e-9 * kn * stretch);
  EXPECT_NEAR(fa.shear, ks * 3e-4, 1e-5 * ks * 3e-4);
}

TEST(ContactBondRelax, ZeroingVelocitiesRemovesTheBondTensionWithoutOvershootAndStops) {
  // Two free spheres bonded at a gap of 0.01 d: the bond pulls them to touching. With the
  // velocities zeroed after each step the gap shrinks monotonically (a steepest-descent walk)
  // and the run stops once the mean unbalanced force no longer decreases.
  Packing p;
  p.box.length = {10, 10, 10};
  p.box.periodic = {false, false, false};
  p.add({4.0, 2, 2}, 0.5);
  p.add({5.01, 2, 2}, 0.5);
  p.bonds.add(0, 1, {0, 0, 0}, 0, 1.01);
  EngineConfig c = config(0.0, inf, inf);
  c.time_step = 0.0;  // automatic: 0.2 sqrt(m / k)
  c.types[0].damping = 0.9;
  Engine e(p, c);
  ZeroVelocityRelaxOptions o;
  o.check_interval = 1;
  o.max_steps = 5000;
  const ZeroVelocityRelaxResult r = relax_zeroing_velocities(e, o);
  EXPECT_TRUE(r.converged) << r.reason();
  EXPECT_LT(r.steps, 5000);
  EXPECT_NEAR(r.initial_unbalanced_force, kn * 0.01, 1e-9 * kn);
  EXPECT_LT(r.final_unbalanced_force, 1e-6 * r.initial_unbalanced_force);
  for (std::size_t k = 1; k < r.unbalanced_force.size(); ++k)
    EXPECT_LE(r.unbalanced_force[k], r.unbalanced_force[k - 1] + 1e-9 * r.initial_unbalanced_force);
  const Packing out = e.packing();
  EXPECT_NEAR(out.position[1].x - out.position[0].x, 1.0, 1e-8);
  EXPECT_NEAR(out.position[0].x + out.position[1].x, 9.01, 1e-12);  // symmetric: no drift
  for (std::size_t k = 0; k < 2; ++k) EXPECT_EQ(norm(e.particles().velocity[k]), 0.0);
}

TEST(ContactBondRelax, FixedParticlesKeepTheirPrescribedVelocity) {
  Packing p = fixed_pair(4.0, false, 0.01);
  p.fixed = {1, 0};
  EngineConfig c = config(0.0, inf, inf);
  c.time_step = 0.0;
  Engine e(p, c);
  std::size_t k0 = e.original_index()[0] == 0 ? 0 : 1;
  e.particles().velocity[k0] = Vec3{0, 0, 1e-3};
  ZeroVelocityRelaxOptions o;
  o.max_steps = 100;
  o.patience = 1000;
  const ZeroVelocityRelaxResult r = relax_zeroing_velocities(e, o);
  EXPECT_EQ(r.steps, 100);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(e.particles().velocity[k0].z, 1e-3);
  EXPECT_NEAR(e.packing().position[0].z, 2.0 + 100 * e.time_step() * 1e-3, 1e-12);
}
