// The near list (dem/near_pairs.cpp) changes which listed pairs the pair loop visits, never
// which act: every case here runs with it and without it (near_margin_ratio = 0) and must give
// the same bits, at several thread counts. Each case first checks that the near list was
// really walked and refreshed, so that a pass is not the whole list being walked.
#include <gtest/gtest.h>

#include <cstdint>
#include <sstream>
#include <vector>

#include "packlab/core/error.hpp"
#include "packlab/core/random.hpp"
#include "packlab/dem/engine.hpp"
#include "packlab/generate/bonding.hpp"
#include "packlab/generate/random.hpp"

using namespace packlab;
using namespace packlab::dem;

namespace {

// A gas: spheres of two sizes on a jittered simple cubic lattice of spacing 1.3 (gaps of
// 0.3 or more, no overlap at the start) with random velocities of about `speed`, so that pairs
// keep meeting and parting while most listed pairs are apart.
Packing gas(int cells, std::uint64_t seed, double speed) {
  Random rng(seed);
  Packing packing;
  const double spacing = 1.3;
  packing.box.length = {cells * spacing, cells * spacing, cells * spacing};
  packing.box.periodic = {true, true, true};
  for (int x = 0; x < cells; ++x)
    for (int y = 0; y < cells; ++y)
      for (int z = 0; z < cells; ++z) {
        const bool small = (x + y + z) % 4 == 0;
        const Vec3 jitter{rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1)};
        packing.add(Vec3{(x + 0.5) * spacing, (y + 0.5) * spacing, (z + 0.5) * spacing} + jitter, small ? 0.3 : 0.5,
                    small ? 1 : 0);
        packing.velocity.push_back({rng.uniform(-speed, speed), rng.uniform(-speed, speed), rng.uniform(-speed, speed)});
      }
  return packing;
}

EngineConfig gas_config() {
  EngineConfig config;
  Material a{1000.0, 300.0, 0.3, 1000.0, 0.05};  // normal, shear stiffness, friction, density, damping
  Material b{600.0, 200.0, 0.5, 700.0, 0.05};
  config.types = {a, b};
  config.time_step_rule = TimeStepRule::stiffness_sum;
  config.adapt_threads = false;
  // A skin of half a diameter: most listed pairs of a gas are then apart, as in a sparse
  // packing, and the near list is walked (it would not be where it keeps most of them).
  config.skin_ratio = 1.0;
  return config;
}

struct Outcome {
  std::vector<Vec3> position, velocity, angular_velocity;
  std::vector<double> kinetic, strain;
  std::vector<std::size_t> contacts;
  std::vector<std::size_t> breaks;
  double time = 0.0;
  friend bool operator==(const Outcome&, const Outcome&) = default;
};

struct NearStats {
  long refreshes = 0;
  double near_fraction = 1.0;  // the smallest share of listed pairs that the near list held at a check
};

// Runs `blocks` x (steps + 1 measured) steps; `between` is called after each block.
template <class Between>
Outcome run(Engine& engine, long blocks, long steps, NearStats* stats, Between between) {
  Outcome out;
  for (long b = 0; b < blocks; ++b) {
    engine.run(steps);
    const Diagnostics d = engine.step_measured();
    out.kinetic.push_back(d.kinetic_energy);
    out.strain.push_back(d.strain_energy);
    out.contacts.push_back(d.contacts);
    if (stats)
      stats->near_fraction =
          std::min(stats->near_fraction, static_cast<double>(engine.near_pairs()) /
                                             static_cast<double>(std::max<std::size_t>(1, engine.listed_pairs())));
    between(engine, b);
  }
  const Packing end = engine.packing();
  out.position = end.position;
  out.velocity = end.velocity;
  out.angular_velocity = end.angular_velocity;
  for (const BondBreak& br : engine.bond_breaks()) out.breaks.push_back(br.bond);
  out.time = engine.time();
  if (stats) stats->refreshes = engine.near_list_refreshes();
  return out;
}

Outcome run(const Packing& packing, EngineConfig config, int threads, long blocks, long steps,
            NearStats* stats = nullptr) {
  config.threads = threads;
  Engine engine(packing, config);
  return run(engine, blocks, steps, stats, [](Engine&, long) {});
}

long total_contacts(const Outcome& o) {
  long sum = 0;
  for (std::size_t c : o.contacts) sum += static_cast<long>(c);
  return sum;
}

}  // namespace

TEST(NearList, AGasGivesTheSameBitsAsWalkingEveryListedPair) {
  const Packing p = gas(11, 11, 0.05);
  EngineConfig whole = gas_config();
  whole.near_margin_ratio = 0.0;
  const Outcome reference = run(p, whole, 1, 8, 60);
  ASSERT_GT(total_contacts(reference), 50) << "the gas must collide to test anything";
  for (int threads : {1, 2, 3}) {
    NearStats stats;
    const Outcome near = run(p, gas_config(), threads, 8, 60, &stats);
    EXPECT_GT(stats.refreshes, 20) << threads << " threads: the near list must be refreshed as the gas moves";
    EXPECT_LT(stats.near_fraction, 0.5) << threads << " threads: the near list must hold a part of the listed pairs";
    EXPECT_TRUE(near.position == reference.position) << threads << " threads: positions differ";
    EXPECT_TRUE(near.velocity == reference.velocity) << threads << " threads: velocities differ";
    EXPECT_TRUE(near.angular_velocity == reference.angular_velocity) << threads << " threads: spins differ";
    EXPECT_TRUE(near.kinetic == reference.kinetic && near.strain == reference.strain &&
                near.contacts == reference.contacts)
        << threads << " threads: measured steps differ";
    EXPECT_EQ(near.time, reference.time);
  }
}

// The margin decides only how often the list is refreshed and how many pairs it holds.
TEST(NearList, EveryMarginGivesTheSameBits) {
  const Packing p = gas(9, 12, 0.08);
  EngineConfig config = gas_config();
  config.near_margin_ratio = 0.0;
  const Outcome reference = run(p, config, 2, 6, 50);
  for (double margin : {0.005, 0.2, 1.0}) {
    config.near_margin_ratio = margin;
    NearStats stats;
    EXPECT_TRUE(run(p, config, 2, 6, 50, &stats) == reference) << "margin " << margin;
    EXPECT_GT(stats.refreshes, 1) << "margin " << margin;
  }
}

// Radii that grow between steps (the void expansion method's increments) make the list stale:
// spheres at rest on a simple cubic lattice (gaps of 0.09, beyond the margin of 0.025), every
// fourth of them growing by twice the margin at a time, so that contacts appear at once while
// nothing moves that would refresh the list.
TEST(NearList, GrowingRadiiAreSeen) {
  Packing p;
  const int cells = 10;
  const double spacing = 1.04;
  p.box.length = {cells * spacing, cells * spacing, cells * spacing};
  p.box.periodic = {true, true, true};
  for (int x = 0; x < cells; ++x)
    for (int y = 0; y < cells; ++y)
      for (int z = 0; z < cells; ++z) {
        const bool grows = (x + 2 * y + 3 * z) % 4 == 0;
        p.add({(x + 0.5) * spacing, (y + 0.5) * spacing, (z + 0.5) * spacing}, grows ? 0.45 : 0.5, grows ? 1 : 0);
      }
  auto grow = [](Engine& e, long b) { e.set_radius_of_type(1, 0.45 + 0.05 * static_cast<double>(b + 1)); };
  EngineConfig whole = gas_config();
  whole.near_margin_ratio = 0.0;
  Engine a(p, whole);
  const Outcome reference = run(a, 4, 30, nullptr, grow);
  ASSERT_GT(total_contacts(reference), 100);
  for (int threads : {1, 2}) {
    EngineConfig config = gas_config();
    config.threads = threads;
    Engine b(p, config);
    NearStats stats;
    const Outcome near = run(b, 4, 30, &stats, grow);
    EXPECT_LT(stats.near_fraction, 0.5);
    EXPECT_TRUE(near == reference) << threads << " threads";
  }
}

// A bonded pair is left out of the near list; when its bond breaks, its contact must act from
// the next step. Two spheres overlapping by a tenth of a diameter, held at rest by a bond of
// that length, slide slowly past each other until the bond fails in shear: the contact then
// pushes them apart, long before the slow motion alone would refresh the near list.
TEST(NearList, TheContactOfABrokenBondActsAtOnce) {
  Packing p;
  p.box.length = {20.0, 20.0, 20.0};
  p.box.periodic = {false, false, false};
  p.add({10.0, 10.0, 10.0}, 0.5, 0);
  p.add({10.9, 10.0, 10.0}, 0.5, 0);
  p.velocity = {{0.0, -1e-4, 0.0}, {0.0, 1e-4, 0.0}};
  p.bonds.add(0, 1, {0, 0, 0}, 0, 0.9);
  EngineConfig config;
  config.types = {Material{1000.0, 100.0, 0.0, 1000.0, 0.0}};
  config.time_step = 0.01;
  config.adapt_threads = false;
  config.threads = 1;
  config.bond_materials = BondMaterialList<ElasticBond>{
      {.youngs_modulus = 2e3, .normal_strength = 1e6, .shear_strength = 1e-2, .relaxation_time = 1e-6}};
  auto trajectory = [&](double margin) {
    EngineConfig c = config;
    c.near_margin_ratio = margin;
    Engine e(p, c);
    std::vector<Vec3> x;
    for (int s = 0; s < 400; ++s) {
      e.run(1);
      x.push_back(e.packing().position[1]);
    }
    EXPECT_EQ(e.bond_breaks().size(), 1u);
    return x;
  };
  const std::vector<Vec3> reference = trajectory(0.0);
  ASSERT_GT(reference.back().x, 11.0) << "the contact must push the spheres apart after the break";
  EXPECT_TRUE(trajectory(0.05) == reference);
}

// Bonded pairs stay out of the near list until their bond breaks; a bond that breaks must
// bring its pair in for the next step.
TEST(NearList, PairsOfBondsThatBreakJoinTheNearList) {
  Random rng(9);
  generate::RandomPackingParams rp;
  rp.particles = 1000;
  rp.radius = 0.5;
  rp.volume_fraction = 0.60;
  Packing p = generate::make_random_packing(rp, rng);
  p.box.periodic = {false, false, false};
  generate::BondingOptions bonding;
  bonding.cutoff_ratio = 1.2;
  generate::add_bonds(p, bonding);
  EngineConfig config;
  config.types = {Material{1000.0, 100.0, 0.3, 1000.0, 0.3}};
  config.time_step_rule = TimeStepRule::stiffness_sum;
  config.adapt_threads = false;
  config.bond_materials =
      BondMaterialList<ElasticBond>{{.youngs_modulus = 2e3, .normal_strength = 40.0, .shear_strength = 40.0,
                                     .relaxation_time = 0.05}};
  double z_min = 1e300, z_max = -1e300;
  for (const Vec3& x : p.position) {
    z_min = std::min(z_min, x.z);
    z_max = std::max(z_max, x.z);
  }
  auto squeezed = [&](EngineConfig c, int threads, NearStats* stats) {
    c.threads = threads;
    Engine e(p, c);
    e.add_wall(Wall{{0, 0, z_min - 0.4}, {0, 0, 1}, {}});
    e.add_wall(Wall{{0, 0, z_max + 0.4}, {0, 0, -1}, {0, 0, -0.05}});
    return run(e, 6, 80, stats, [](Engine&, long) {});
  };
  EngineConfig whole = config;
  whole.near_margin_ratio = 0.0;
  const Outcome reference = squeezed(whole, 1, nullptr);
  ASSERT_GT(reference.breaks.size(), 10u) << "the case must break bonds";
  for (int threads : {1, 2, 3}) {
    NearStats stats;
    const Outcome near = squeezed(config, threads, &stats);
    EXPECT_LT(stats.near_fraction, 0.5) << threads << " threads: bonded pairs must stay out of the near list";
    EXPECT_TRUE(near == reference) << threads << " threads";
  }
}

// A checkpoint does not hold the near list: a loaded engine refreshes it and goes on bit for bit.
TEST(NearList, ACheckpointMidRunContinuesBitForBit) {
  const Packing p = gas(10, 14, 0.05);
  const EngineConfig config = gas_config();
  Engine straight(p, config);
  straight.run(300);
  std::stringstream state;
  straight.save_state(state);
  straight.run(300);
  Engine resumed(p, config);
  resumed.load_state(state);
  resumed.run(300);
  EXPECT_LT(resumed.near_pairs(), resumed.listed_pairs() / 2);
  EXPECT_TRUE(resumed.packing().position == straight.packing().position);
  EXPECT_TRUE(resumed.packing().velocity == straight.packing().velocity);
  EXPECT_TRUE(resumed.packing().angular_velocity == straight.packing().angular_velocity);
}

TEST(NearList, AMarginOutsideZeroToOneIsRefused) {
  EngineConfig config = gas_config();
  config.near_margin_ratio = -0.1;
  EXPECT_THROW(Engine(gas(4, 1, 0.0), config), InputError);
  config.near_margin_ratio = 1.5;
  EXPECT_THROW(Engine(gas(4, 1, 0.0), config), InputError);
}
