// One result per seed whatever the thread count (dem/step.cpp: every particle's force is
// summed in the single-thread order; sums over particles run over fixed chunks). Compared bit
// for bit at 1, 2, 3 and 5 threads, on the cases every command uses: pair contacts in a
// periodic box, two particle types, Hertz-Mindlin with the contacts time-step rule, bonds
// that break, walls that move.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "packlab/core/error.hpp"
#include "packlab/core/random.hpp"
#include "packlab/dem/engine.hpp"
#include "packlab/generate/bonding.hpp"
#include "packlab/generate/random.hpp"

using namespace packlab;
using namespace packlab::dem;

namespace {

Packing dense_random(long n, double phi, std::uint64_t seed, bool periodic = true) {
  Random rng(seed);
  generate::RandomPackingParams p;
  p.particles = n;
  p.radius = 0.5;
  p.volume_fraction = phi;
  Packing packing = generate::make_random_packing(p, rng);
  if (!periodic) packing.box.periodic = {false, false, false};
  return packing;
}

// Everything a run leaves behind, to compare bit for bit.
struct Outcome {
  std::vector<Vec3> position, velocity, angular_velocity;
  std::vector<double> kinetic, strain, contacts, unbalanced;
  std::vector<Vec3> wall_force;
  std::vector<std::size_t> breaks;
  std::vector<Vec3> break_position;
  double time = 0.0;
  friend bool operator==(const Outcome&, const Outcome&) = default;
};

Outcome run(const Packing& packing, EngineConfig config, int threads, long blocks, long steps_per_block,
            bool with_walls = false, long* switches = nullptr) {
  config.threads = threads;
  Engine engine(packing, config);
  if (with_walls) {
    double z_min = 1e300, z_max = -1e300;
    for (const Vec3& x : packing.position) {
      z_min = std::min(z_min, x.z);
      z_max = std::max(z_max, x.z);
    }
    engine.add_wall(Wall{{0, 0, z_min - 0.4}, {0, 0, 1}, {}});
    engine.add_wall(Wall{{0, 0, z_max + 0.4}, {0, 0, -1}, {0, 0, -0.02}});
  }
  Outcome out;
  for (long b = 0; b < blocks; ++b) {
    engine.run(steps_per_block);
    const Diagnostics d = engine.step_measured();
    out.kinetic.push_back(d.kinetic_energy);
    out.strain.push_back(d.strain_energy);
    out.contacts.push_back(static_cast<double>(d.contacts));
    out.unbalanced.push_back(d.unbalanced_force_ratio);
    for (std::size_t w = 0; w < engine.wall_count(); ++w) out.wall_force.push_back(engine.wall_force(w));
  }
  const Packing end = engine.packing();
  out.position = end.position;
  out.velocity = end.velocity;
  out.angular_velocity = end.angular_velocity;
  for (const BondBreak& b : engine.bond_breaks()) {
    out.breaks.push_back(b.bond);
    out.break_position.push_back(b.position);
  }
  out.time = engine.time();
  if (switches) *switches = engine.thread_switches();
  return out;
}

void expect_same_at_every_thread_count(const Packing& packing, EngineConfig config, long blocks, long steps,
                                       bool with_walls = false) {
  config.adapt_threads = false;  // each count for every step (adaptation: its own test below)
  const Outcome one = run(packing, config, 1, blocks, steps, with_walls);
  for (int threads : {2, 3, 5}) {
    const Outcome many = run(packing, config, threads, blocks, steps, with_walls);
    EXPECT_TRUE(many.position == one.position) << threads << " threads: positions differ";
    EXPECT_TRUE(many.angular_velocity == one.angular_velocity) << threads << " threads: spins differ";
    EXPECT_TRUE(many.kinetic == one.kinetic && many.strain == one.strain && many.unbalanced == one.unbalanced)
        << threads << " threads: measured energies differ";
    EXPECT_TRUE(many.wall_force == one.wall_force) << threads << " threads: wall forces differ";
    EXPECT_TRUE(many.breaks == one.breaks) << threads << " threads: bond breaks differ";
    EXPECT_TRUE(many.break_position == one.break_position) << threads << " threads: break positions differ";
    EXPECT_EQ(many.time, one.time) << threads << " threads";
  }
}

// An open bonded block (1,000 particles, bonds within 1.2 diameters) and an elastic bond law
// whose bonds break when two walls squeeze it (run(..., with_walls = true)).
Packing bonded_block() {
  Packing p = dense_random(1000, 0.60, 9, false);
  generate::BondingOptions bonding;
  bonding.cutoff_ratio = 1.2;
  generate::add_bonds(p, bonding);
  return p;
}

EngineConfig bonded_block_config(TimeStepRule rule) {
  EngineConfig config;
  config.types = {Material{1000.0, 100.0, 0.3, 1000.0, 0.3}};
  config.time_step_rule = rule;
  config.bond_materials =
      BondMaterialList<ElasticBond>{{.youngs_modulus = 2e3, .normal_strength = 40.0, .shear_strength = 40.0}};
  return config;
}

}  // namespace

TEST(ThreadCount, PairContactsInAPeriodicBoxAreTheSameBitForBit) {
  const Packing p = dense_random(1500, 0.68, 5);
  EngineConfig config;
  config.types = {Material{1000.0, 10.0, 0.1, 1000.0, 0.7}};
  expect_same_at_every_thread_count(p, config, 4, 60);
}

TEST(ThreadCount, TwoTypesHertzMindlinAndTheContactsRuleAreTheSameBitForBit) {
  Packing p = dense_random(1200, 0.66, 7);
  for (std::size_t i = 0; i < p.size(); i += 3) {
    p.type[i] = 1;
    p.radius[i] = 0.35;
  }
  EngineConfig config;
  config.contact_law = "hertz_mindlin";
  Material a{}, b{};
  a.youngs_modulus = 1e6, a.poisson_ratio = 0.25, a.restitution = 0.5, a.friction = 0.3, a.density = 1000;
  a.rolling_friction = 0.01, a.damping = 0.2;
  b = a;
  b.youngs_modulus = 3e6, b.density = 2500;
  config.types = {a, b};
  config.time_step_rule = TimeStepRule::contacts;
  expect_same_at_every_thread_count(p, config, 4, 50);
}

TEST(ThreadCount, BreakingBondsBetweenMovingWallsAreTheSameBitForBit) {
  // An open bonded block squeezed between two walls (the top one moving down) with the
  // stiffness-sum time-step rule: bonds cross thread ranges, some break, walls touch
  // particles of every range.
  const Packing p = bonded_block();
  ASSERT_GT(p.bonds.size(), 1000u);
  EngineConfig config = bonded_block_config(TimeStepRule::stiffness_sum);
  const Outcome one = run(p, config, 1, 5, 80, true);
  ASSERT_GT(one.breaks.size(), 0u) << "the case must break bonds to test their order";
  expect_same_at_every_thread_count(p, config, 5, 80, true);
}

// At a fixed time step an unmeasured step integrates inside the force region, each thread its
// own particles as soon as it is done with them (dem/step.cpp): the same case as above with
// the global rule, where the break positions must still be those before the particles moved.
TEST(ThreadCount, BreakingBondsBetweenMovingWallsAtAFixedTimeStepAreTheSameBitForBit) {
  const Packing p = bonded_block();
  EngineConfig config = bonded_block_config(TimeStepRule::global);
  const Outcome one = run(p, config, 1, 5, 80, true);
  ASSERT_GT(one.breaks.size(), 0u) << "the case must break bonds to test their order and positions";
  expect_same_at_every_thread_count(p, config, 5, 80, true);
}

// adapt_threads: an engine that probes one thread against three every millisecond (and runs at
// whichever was faster) switches its thread count many times and still gives the bits of a
// single-thread run, bonds breaking and walls moving included.
TEST(ThreadCount, SwitchingBetweenOneAndSeveralThreadsMidRunChangesNoBit) {
  const Packing p = bonded_block();
  EngineConfig config = bonded_block_config(TimeStepRule::stiffness_sum);
  config.adapt_threads = false;
  const Outcome one = run(p, config, 1, 5, 80, true);
  ASSERT_GT(one.breaks.size(), 0u);
  config.adapt_threads = true;
  config.thread_probe_every = 1e-3;
  config.thread_probe_seconds = 1e-3;
  long switches = 0;
  const Outcome adaptive = run(p, config, 3, 5, 80, true, &switches);
  // A probe switches to the other count and back twice (4 switches) after step 300; its four
  // stretches of 12 steps (2 untimed) and 1 ms fit in the 100 steps left on any machine.
  EXPECT_GE(switches, 4);
  EXPECT_TRUE(adaptive == one) << "a mid-run switch of the thread count changed the result";
}

TEST(ThreadCount, ProbeTimesThatAreNotPositiveAreRefused) {
  EngineConfig config;
  config.thread_probe_every = 0.0;
  EXPECT_THROW(Engine(dense_random(100, 0.5, 1), config), InputError);
  config.thread_probe_every = 20.0;
  config.thread_probe_seconds = -1.0;
  EXPECT_THROW(Engine(dense_random(100, 0.5, 1), config), InputError);
}
