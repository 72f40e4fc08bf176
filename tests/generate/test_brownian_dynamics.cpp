// Brownian-dynamics coagulation (generate/brownian_dynamics.hpp) against what does not depend on
// the paper: free spheres diffuse with the Stokes-Einstein coefficient (MSD = 6 D_0 t, 2 D_0 t per
// axis), the Debye length of a 1:1 electrolyte, a suspension without a barrier coagulates while
// one behind a 60 kT barrier stays dispersed, bonds are stiff and never overlap, a checkpointed
// run continues bit for bit, the thread count changes nothing (one thread runs the serial loop,
// several the per-pair slots: two code paths, one result), and bad input is one message naming
// the key.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "../input_error.hpp"
#include "packlab/generate/brownian_dynamics.hpp"

using namespace packlab;
using namespace packlab::generate;

namespace {

BdParams dense(double psi) {
  BdParams p;
  p.particles = 250;
  p.volume_fraction = 0.4;
  p.surface_potential = psi;
  p.duration = 0.02;
  p.samples = 10;
  return p;
}

void expect_same_bits(const BdResult& r, const BdResult& expected, const std::string& what) {
  ASSERT_EQ(r.packing.size(), expected.packing.size()) << what;
  for (std::size_t i = 0; i < r.packing.size(); ++i) {
    EXPECT_EQ(r.packing.position[i].x, expected.packing.position[i].x) << what << " sphere " << i;
    EXPECT_EQ(r.packing.position[i].y, expected.packing.position[i].y) << what << " sphere " << i;
    EXPECT_EQ(r.packing.position[i].z, expected.packing.position[i].z) << what << " sphere " << i;
  }
  EXPECT_EQ(r.packing.bonds.i, expected.packing.bonds.i) << what;
  EXPECT_EQ(r.packing.bonds.j, expected.packing.bonds.j) << what;
  EXPECT_EQ(r.status.step, expected.status.step) << what;
}

}  // namespace

TEST(BrownianDynamics, FreeSpheresDiffuseWithTheStokesEinsteinCoefficient) {
  BdParams p;
  p.particles = 4000;
  p.volume_fraction = 0.002;  // dilute: a few collisions at most
  p.hamaker_constant = 0.0;   // no DLVO force: free diffusion
  p.surface_potential = 0.0;
  p.bond_separation = 1e-12;
  p.time_step = 0.01 * p.diffusion_time();  // any step is exact for free diffusion
  p.duration = 1.0;
  p.samples = 10;
  const BdResult r = brownian_dynamics(p, 7);
  const double d0 = 1.380649e-23 * 298.15 / (6 * std::numbers::pi * 0.89e-3 * 0.25e-6);
  EXPECT_NEAR(p.diffusion_coefficient(), d0, 1e-12 * d0);
  ASSERT_EQ(r.log.size(), 11u);
  // sqrt(2/3) / sqrt(N) = 1.3 % standard error of the mean squared displacement: 5 % is 4 sigma.
  for (std::size_t k = 1; k < r.log.size(); ++k)
    EXPECT_NEAR(r.log[k].msd / (6 * d0 * r.log[k].time), 1.0, 0.05) << "t = " << r.log[k].reduced_time;
  EXPECT_NEAR(r.status.msd / (6 * d0 * r.status.time), 1.0, 0.03);
  EXPECT_NEAR(r.status.reduced_time, 1.0, 1e-12);
}

TEST(BrownianDynamics, DebyeLengthOfAMillimolarMonovalentSaltIsNineSixNanometres) {
  // 1/kappa = 0.304 nm / sqrt(I [mol/L]) for a 1:1 electrolyte in water at 25 C (Israelachvili).
  EXPECT_NEAR(debye_length_from_ionic_strength(1.0, 78.5, 298.15), 0.304e-9 / std::sqrt(1e-3), 0.01 * 9.6e-9);
  BdParams p;
  p.ionic_strength = 1.0;
  EXPECT_NEAR(p.screening_length(), 9.62e-9, 0.01e-9);
}

TEST(BrownianDynamics, CoagulatesWithoutABarrierAndStaysDispersedBehindAHighOne) {
  const BdResult fast = brownian_dynamics(dense(0.0), 3);
  const BdResult stable = brownian_dynamics(dense(40e-3), 3);  // barrier ~ 60 kT
  EXPECT_GT(fast.status.bonds, 100);
  EXPECT_LT(fast.status.clusters, 200);
  EXPECT_EQ(stable.status.bonds, 0);
  EXPECT_EQ(stable.status.clusters, 250);
  // Bonded pairs sit at 2a + bond_separation within a few thermal stretches sqrt(kT / k_b).
  const Packing& pk = fast.packing;
  const double stretch = std::sqrt(1.380649e-23 * 298.15 / fast.bond_stiffness);
  for (std::size_t b = 0; b < pk.bonds.i.size(); ++b) {
    const Vec3 d = pk.position[static_cast<std::size_t>(pk.bonds.j[b])] + pk.box.shift_vector(pk.bonds.image[b]) -
                   pk.position[static_cast<std::size_t>(pk.bonds.i[b])];
    EXPECT_NEAR(norm(d), 2 * 0.25e-6 + 1e-9, 8 * stretch) << b;
  }
}

TEST(BrownianDynamics, CheckpointContinuesBitForBitAndThreadsChangeNothing) {
  BdParams p = dense(15e-3);
  p.duration = 0.01;
  const BdResult straight = brownian_dynamics(p, 11);
  BdRun first(p, Random(11));
  first.run(first.total_steps() / 2);
  std::stringstream state;
  first.save_state(state);
  BdRun resumed = BdRun::load_state(state, 2);
  ASSERT_EQ(resumed.params().threads, 2);
  resumed.run();
  expect_same_bits(resumed.result(), straight, "1 thread, then resumed on 2");
  // Coagulating runs (many bonds formed while the threads share the pairs), both bond models,
  // at 1, 2 and 3 threads; 250 spheres are 4 chunks of the pair loop, so every thread has work.
  for (const int model : {0, 1, 2}) {  // rigid, central, slip bonds
    BdParams q = dense(0.0);
    q.duration = 0.005;
    q.central_bonds = model == 1;
    q.bond_slip_force = model == 2 ? 3e-12 : 0.0;  // N: about the thermal bond force, some slip
    const BdResult one = brownian_dynamics(q, 5);
    EXPECT_GT(one.status.bonds, 100) << model;
    for (const int threads : {2, 3}) {
      q.threads = threads;
      expect_same_bits(brownian_dynamics(q, 5), one, fmt::format("bond model {} threads {}", model, threads));
    }
  }
  // A damaged state is one InputError.
  std::string bytes = state.str();
  std::istringstream truncated(bytes.substr(0, bytes.size() / 2));
  EXPECT_FALSE(test::error_of([&] { BdRun::load_state(truncated); }).empty());
}

// The slip bond's return mapping against its geometry: within the limit d_0 stays; beyond it
// the new d_0 keeps its length L_0, lies in the plane of d_0 and d on d_0's side, its part
// normal to d is exactly the limit (the tangential force k_b |.| is F_s), and mapping it again
// changes nothing.
TEST(BrownianDynamics, SlipBondTurnsItsRestDirectionUntilTheTangentialForceIsTheSlipForce) {
  const double length = 5.01e-7;
  const Vec3 rest{length, 0.0, 0.0};
  const Vec3 d = 1.002 * length * Vec3{std::cos(0.3), std::sin(0.3), 0.0};  // rolled by 0.3 rad
  const Vec3 n = (1.0 / norm(d)) * d;
  const double offset_now = norm(rest - dot(rest, n) * n);  // L_0 sin 0.3
  EXPECT_NEAR(offset_now, length * std::sin(0.3), 1e-12 * length);
  const Vec3 kept = slip_bond_rest(rest, d, length, 1.01 * offset_now);
  EXPECT_EQ(kept.x, rest.x);
  EXPECT_EQ(kept.y, rest.y);
  const double limit = 0.1 * offset_now;
  const Vec3 slipped = slip_bond_rest(rest, d, length, limit);
  EXPECT_NEAR(norm(slipped), length, 1e-12 * length);
  EXPECT_NEAR(norm(slipped - dot(slipped, n) * n), limit, 1e-12 * length);
  EXPECT_EQ(slipped.z, 0.0);
  // Between d_0 and d: turned by 0.3 rad less the angle the limit leaves, asin(0.1 sin 0.3).
  EXPECT_NEAR(std::atan2(slipped.y, slipped.x), 0.3 - std::asin(0.1 * std::sin(0.3)), 1e-12);
  const Vec3 again = slip_bond_rest(slipped, d, length, limit);
  EXPECT_NEAR(norm(again - slipped), 0.0, 1e-12 * length);
}

// A slip force no bond reaches gives the rigid run bit for bit; a tiny one lets the aggregates
// restructure as central bonds do: more bonds than rigid ones form in the same time.
TEST(BrownianDynamics, SlipBondsLieBetweenRigidAndCentralBonds) {
  BdParams q = dense(0.0);
  q.duration = 0.02;
  const BdResult rigid = brownian_dynamics(q, 9);
  q.bond_slip_force = 1.0;  // N: far beyond any force here
  expect_same_bits(brownian_dynamics(q, 9), rigid, "slip force 1 N");
  q.bond_slip_force = 1e-20;
  const BdResult slipping = brownian_dynamics(q, 9);
  q.bond_slip_force = 0.0;
  q.central_bonds = true;
  const BdResult central = brownian_dynamics(q, 9);
  EXPECT_GT(slipping.status.bonds, rigid.status.bonds);
  EXPECT_GT(central.status.bonds, rigid.status.bonds);
  EXPECT_LT(std::abs(slipping.status.bonds - central.status.bonds), slipping.status.bonds - rigid.status.bonds);
}

TEST(BrownianDynamics, BadInputNamesTheKeyAndItsRange) {
  BdParams p;
  p.volume_fraction = 0.7;
  EXPECT_NE(test::error_of([&] { p.validate(); }).find("volume_fraction"), std::string::npos);
  p = BdParams{};
  p.particles = 10;  // box smaller than twice the interaction range
  EXPECT_NE(test::error_of([&] { p.validate(); }).find("particles"), std::string::npos);
  p = BdParams{};
  p.bond_separation = 1e-6;
  EXPECT_NE(test::error_of([&] { p.validate(); }).find("bond_separation"), std::string::npos);
  p = BdParams{};
  p.central_bonds = true;
  p.bond_slip_force = 1e-12;
  EXPECT_NE(test::error_of([&] { p.validate(); }).find("bond_slip_force"), std::string::npos);
}
