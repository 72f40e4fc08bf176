// Renumbering the particles of a running engine along the space-filling curve
// (EngineConfig::resort_particles, Engine::sort_particles; dem/resort.cpp): the contact
// histories follow their pairs (reversed where a pair's particles swap roles), the result does
// not depend on the thread count, and a checkpoint taken after a sort resumes bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <tuple>
#include <vector>

#include "../test_packings.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/random.hpp"
#include "packlab/dem/engine.hpp"
#include "packlab/generate/random.hpp"

using namespace packlab;
using namespace packlab::dem;

namespace {

// A sheared gas: spheres of two sizes at volume fraction 0.45 drifting in layers (velocity
// along x growing with z), so that they diffuse out of their sorted order and their contacts
// slide (friction 0.4: shear springs at the Coulomb limit and below).
Packing drifting_gas(long n, std::uint64_t seed) {
  Random rng(seed);
  generate::RandomPackingParams p;
  p.particles = n;
  p.radius = 0.5;
  p.volume_fraction = 0.45;
  Packing packing = generate::make_random_packing(p, rng);
  packing.velocity.resize(packing.size());
  for (std::size_t i = 0; i < packing.size(); ++i) {
    if (i % 3 == 0) {
      packing.type[i] = 1;
      packing.radius[i] = 0.35;
    }
    const double shear = 0.2 * (packing.position[i].z / packing.box.length[2] - 0.5);
    packing.velocity[i] = {shear + rng.uniform(-0.02, 0.02), rng.uniform(-0.02, 0.02), rng.uniform(-0.02, 0.02)};
  }
  return packing;
}

EngineConfig config_for(int threads, bool resort) {
  EngineConfig config;
  config.types = {Material{1000.0, 400.0, 0.4, 1000.0, 0.02}, Material{700.0, 300.0, 0.4, 800.0, 0.02}};
  config.time_step_rule = TimeStepRule::stiffness_sum;
  config.threads = threads;
  config.adapt_threads = false;
  config.resort_particles = resort;
  return config;
}

// Contact forces keyed by the packing's indices of the two particles (smaller first) and the
// force on the larger-index one.
std::map<std::pair<int, int>, Vec3> contacts_by_pair(const ContactForces& f) {
  std::map<std::pair<int, int>, Vec3> out;
  for (std::size_t c = 0; c < f.size(); ++c) {
    if (f.kind[c] != ContactForces::contact) continue;
    const bool ordered = f.i[c] < f.j[c];
    out[{std::min(f.i[c], f.j[c]), std::max(f.i[c], f.j[c])}] = ordered ? f.force[c] : -f.force[c];
  }
  return out;
}

}  // namespace

TEST(Resort, HistoriesFollowTheirPairsThroughARenumbering) {
  Engine e(drifting_gas(1500, 3), config_for(1, false));
  e.run(400);
  const auto before = contacts_by_pair(e.contact_forces());
  const std::vector<int> order_before = e.original_index();
  e.sort_particles();
  ASSERT_NE(e.original_index(), order_before) << "the gas must have left its sorted order";
  const auto after = contacts_by_pair(e.contact_forces());
  ASSERT_EQ(after.size(), before.size());
  // Some pair's particles must have swapped roles, and carry shear: a history left as it was
  // for them would point the wrong way.
  long swapped_with_shear = 0;
  const std::vector<int>& order = e.original_index();
  std::vector<int> engine_index(order.size()), old_engine_index(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    engine_index[static_cast<std::size_t>(order[k])] = static_cast<int>(k);
    old_engine_index[static_cast<std::size_t>(order_before[k])] = static_cast<int>(k);
  }
  // A pair's distance is computed from the other end after a swap: it can differ by a few
  // rounding units of the coordinates (box ~12 m), the normal force by k_n (1000 N/m) times that.
  const double distance_rounding = 1000.0 * 8.0 * 2.2e-16 * e.packing().box.length[0];
  for (const auto& [pair, force] : before) {
    const auto it = after.find(pair);
    ASSERT_NE(it, after.end());
    const double scale = norm(force);
    EXPECT_LE(norm(it->second - force), 1e-12 * scale + distance_rounding)
        << "pair " << pair.first << "-" << pair.second;
    const bool was_first = old_engine_index[pair.first] < old_engine_index[pair.second];
    const bool is_first = engine_index[pair.first] < engine_index[pair.second];
    swapped_with_shear += was_first != is_first;
  }
  EXPECT_GT(swapped_with_shear, 10);
}

TEST(Resort, AGasSortedDuringTheRunIsTheSameAtEveryThreadCount) {
  const Packing p = drifting_gas(2000, 4);
  auto run = [&](int threads, long* sorts) {
    Engine e(p, config_for(threads, true));
    std::vector<double> kinetic;
    for (int b = 0; b < 12; ++b) {
      e.run(150);
      kinetic.push_back(e.step_measured().kinetic_energy);
    }
    if (sorts) *sorts = e.particle_resorts();
    const Packing end = e.packing();
    return std::make_tuple(end.position, end.velocity, end.angular_velocity, kinetic);
  };
  long sorts = 0;
  const auto one = run(1, &sorts);
  ASSERT_GT(sorts, 0) << "the gas must drift far enough to be sorted again";
  for (int threads : {2, 3}) EXPECT_TRUE(run(threads, nullptr) == one) << threads << " threads";
}

TEST(Resort, ACheckpointAfterASortResumesBitForBit) {
  const Packing p = drifting_gas(1500, 5);
  const EngineConfig config = config_for(2, true);
  Engine straight(p, config);
  long steps = 0;
  while (straight.particle_resorts() == 0 && steps < 20000) {
    straight.run(100);
    steps += 100;
  }
  ASSERT_GT(straight.particle_resorts(), 0);
  std::stringstream state;
  straight.save_state(state);
  straight.run(1500);
  Engine resumed(p, config);
  resumed.load_state(state);
  resumed.run(1500);
  EXPECT_EQ(resumed.particle_resorts(), straight.particle_resorts());
  EXPECT_TRUE(resumed.particles().position == straight.particles().position);
  EXPECT_TRUE(resumed.packing().velocity == straight.packing().velocity);
  EXPECT_TRUE(resumed.packing().angular_velocity == straight.packing().angular_velocity);
}

TEST(Resort, ABondedModelKeepsItsOrder) {
  Packing p = test::open_cube(8);
  for (int k = 0; k < 8; ++k) p.add({1.0 + (k % 2) * 1.9, 1.0 + (k / 2 % 2) * 1.9, 1.0 + (k / 4) * 1.9}, 1.0);
  p.bonds.add(0, 1, {0, 0, 0}, 0, 1.9);
  EngineConfig config;
  config.bond_materials = BondMaterialList<ContactBond>{{800.0, 80.0, 1e9, 1e9}};
  Engine e(p, config);
  EXPECT_THROW(e.sort_particles(), InputError);
}
