// Radius growth, the contacts time-step rule and exact checkpoints.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>

#include "../input_error.hpp"
#include "../test_packings.hpp"
#include "checkpoint.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/random.hpp"
#include "packlab/dem/engine.hpp"
#include "packlab/generate/random.hpp"

using namespace packlab;
using namespace packlab::dem;

namespace {

Packing two_types(long n, std::uint64_t seed) {
  Random rng(seed);
  generate::RandomPackingParams p;
  p.particles = n;
  p.radius = 0.5;
  p.volume_fraction = 0.6;
  Packing packing = generate::make_random_packing(p, rng);
  for (std::size_t i = 0; i < packing.size(); i += 4) {
    packing.type[i] = 1;
    packing.radius[i] = 0.1;
  }
  return packing;
}

EngineConfig two_type_config() {
  EngineConfig c;
  c.types = {Material{1000.0, 100.0, 0.3, 1000.0, 0.7}, Material{100.0, 1.0, 0.0, 100.0, 0.7}};
  c.threads = 2;
  c.adapt_threads = false;  // two threads from the first step (an adapting engine starts at one)
  return c;
}

}  // namespace

TEST(EngineState, CheckpointContinuesBitwiseIdentically) {
  // N steps + save + load into a fresh engine + N steps == 2N steps, bit for bit.
  test::expect_checkpoint_continues_bitwise(two_types(600, 4), two_type_config(), 200);
}

// Per-particle densities from the input are the one per-particle mass source the engine keeps
// besides the types (issue #14): they survive a checkpoint.
TEST(EngineState, CheckpointWithInputDensitiesContinuesBitwiseIdentically) {
  Packing p = two_types(600, 6);
  p.density.assign(p.size(), 1000.0);
  for (std::size_t i = 0; i < p.size(); i += 3) p.density[i] = 2500.0;
  test::expect_checkpoint_continues_bitwise(p, two_type_config(), 200);
  // A state of the packing with densities does not load into an engine of the one without.
  std::stringstream state;
  Engine(p, two_type_config()).save_state(state);
  Packing plain = p;
  plain.density.clear();
  Engine other(plain, two_type_config());
  const std::string message = test::error_of([&] { other.load_state(state); });
  EXPECT_NE(message.find("per-particle densities"), std::string::npos) << message;
}

// Without friction and bonds the contacts take their central form and the listed pairs keep no
// shear history (issue #14: 24 bytes per listed pair): none is held, carried over, re-sorted or
// checkpointed, and a checkpoint still continues bit for bit, through rebuilds and sorts.
TEST(EngineState, FrictionlessRunKeepsNoPairHistoryAndItsCheckpointContinuesBitwise) {
  EngineConfig with_friction = two_type_config();
  with_friction.resort_particles = true;
  EngineConfig frictionless = with_friction;
  frictionless.types[0].friction = 0.0;
  Packing p = two_types(600, 8);
  Random rng(9);
  p.velocity.assign(p.size(), Vec3{});
  for (auto& v : p.velocity) v = 0.5 * rng.unit_vector();  // a gas: rebuilds and sorts
  Engine frictional(p, with_friction);
  EXPECT_GT(frictional.memory().contact_history, 0u);
  Engine engine(p, frictionless);
  EXPECT_EQ(engine.memory().contact_history, 0u);
  const long builds = engine.neighbor_builds();
  engine.run(400);
  EXPECT_GT(engine.neighbor_builds(), builds);
  EXPECT_GT(engine.particle_resorts(), 0);
  EXPECT_EQ(engine.memory().contact_history, 0u);
  test::expect_checkpoint_continues_bitwise(p, frictionless, 200);
  // A checkpoint with a (zero) history per listed pair, as engines wrote before 2026-12-04:
  // read, the histories dropped, and the run goes on as from the engine's own state.
  std::stringstream with_histories;
  frictional.save_state(with_histories);  // step 0: every history zero, one per listed pair
  Engine resumed(p, frictionless), straight(p, frictionless);
  resumed.load_state(with_histories);
  EXPECT_EQ(resumed.memory().contact_history, 0u);
  resumed.run(200);
  straight.run(200);
  EXPECT_TRUE(resumed.particles().position == straight.particles().position);
  EXPECT_TRUE(resumed.particles().velocity == straight.particles().velocity);
}

TEST(EngineState, DamagedOrForeignCheckpointIsAnInputError) {
  const Packing p = two_types(100, 5);
  Engine e(p, two_type_config());
  std::stringstream state;
  e.save_state(state);
  const std::string bytes = state.str();
  std::stringstream truncated(bytes.substr(0, bytes.size() / 2));
  Engine target(p, two_type_config());
  EXPECT_THROW(target.load_state(truncated), InputError);
  std::stringstream garbage("this is not a checkpoint at all, just text");
  EXPECT_THROW(target.load_state(garbage), InputError);
  Engine other(two_types(104, 5), two_type_config());
  std::stringstream again(bytes);
  EXPECT_THROW(other.load_state(again), InputError);
  // An earlier version's state: the refusal names its format and this version's.
  std::string older = bytes;
  ASSERT_EQ(older.substr(0, 8), "PDEMECK5");
  older[7] = '4';
  std::stringstream old_state(older);
  const std::string message = test::error_of([&] { target.load_state(old_state); });
  EXPECT_NE(message.find("header PDEMECK4"), std::string::npos) << message;
  EXPECT_NE(message.find("reads PDEMECK5"), std::string::npos) << message;
}

TEST(EngineState, GrowingRadiusScalesMassAtConstantDensity) {
  Packing p;
  p.box.length = {10, 10, 10};
  p.add({2, 2, 2}, 0.5, 0);
  p.add({6, 6, 6}, 0.1, 1);
  Engine e(p, two_type_config());
  e.set_radius_of_type(1, 0.3);
  const Packing out = e.packing();
  EXPECT_DOUBLE_EQ(out.radius[1], 0.3);
  EXPECT_DOUBLE_EQ(out.radius[0], 0.5);
  for (std::size_t k = 0; k < 2; ++k) {
    const auto& P = e.particles();
    const double r = P.radius[k];
    const double rho = P.type[k] == 1 ? 100.0 : 1000.0;
    EXPECT_NEAR(P.mass[k], rho * 4.0 / 3.0 * std::numbers::pi * r * r * r, 1e-12 * P.mass[k]);
    const double inertia = 0.4 * P.mass[k] * r * r;
    EXPECT_NEAR(P.inverse_inertia[k], 1.0 / inertia, 1e-12 / inertia);
  }
  EXPECT_THROW(e.set_radius_of_type(1, -1.0), InputError);
}

TEST(EngineState, ContactsRuleFollowsTheLightestTouchingParticle) {
  // A heavy pair touching, and a tiny light particle far away: the step is set by the heavy
  // pair; once the tiny one touches, by the tiny one.
  Packing p = test::open_cube(20);
  p.add({5.0, 5, 5}, 0.5, 0);
  p.add({5.95, 5, 5}, 0.5, 0);
  p.add({15, 15, 15}, 0.01, 1);
  EngineConfig c = two_type_config();
  c.time_step_rule = TimeStepRule::contacts;
  c.threads = 1;
  Engine e(p, c);
  e.run(1);
  const double m_heavy = 1000.0 * 4.0 / 3.0 * std::numbers::pi * 0.125;
  const double k_heavy = combine_stiffness(1000.0, 1000.0, StiffnessRule::particle);
  EXPECT_NEAR(e.time_step(), 0.2 * std::sqrt(m_heavy / k_heavy), 1e-12);
  // Global rule for comparison: limited by the tiny particle although it touches nothing.
  c.time_step_rule = TimeStepRule::global;
  Engine g(p, c);
  EXPECT_LT(g.time_step(), 1e-2 * e.time_step());
  // Move the tiny one onto the heavy pair.
  p.position[2] = {5.0, 5.5, 5};
  Engine touching(p, [&] {
    EngineConfig cc = c;
    cc.time_step_rule = TimeStepRule::contacts;
    return cc;
  }());
  touching.run(1);
  const double m_tiny = 100.0 * 4.0 / 3.0 * std::numbers::pi * 1e-6;
  const double k_mixed = combine_stiffness(1000.0, 100.0, StiffnessRule::particle);
  EXPECT_NEAR(touching.time_step(), 0.2 * std::sqrt(m_tiny / k_mixed), 1e-12 * touching.time_step());
}
