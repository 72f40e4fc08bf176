// The Verlet list must hold exactly the pairs a brute-force search over all pairs and
// periodic images finds, for periodic and open boxes, tiny and elongated ones.
#include <gtest/gtest.h>

#include <algorithm>

#include "packlab/core/error.hpp"
#include "packlab/core/neighbor_list.hpp"
#include "packlab/core/random.hpp"

using namespace packlab;

namespace {

struct Case {
  const char* name;
  Vec3 length;
  std::array<bool, 3> periodic;
  int particles;
};

void random_spheres(const Box& box, int n, Random& rng, std::vector<Vec3>& pos, std::vector<double>& rad) {
  pos.clear();
  rad.clear();
  for (int i = 0; i < n; ++i) {
    // Open axes: some particles outside the nominal box too.
    Vec3 p;
    for (int a = 0; a < 3; ++a)
      p[a] = box.periodic[a] ? rng.uniform(-box.length[a], 2 * box.length[a]) : rng.uniform(-0.2, 1.2) * box.length[a];
    pos.push_back(p);
    rad.push_back(rng.uniform(0.2, 0.5));  // polydisperse, max diameter 1
  }
}

}  // namespace

class NeighborListVsBruteForce : public ::testing::TestWithParam<Case> {};

TEST_P(NeighborListVsBruteForce, SamePairs) {
  const Case c = GetParam();
  Box box;
  box.length = c.length;
  box.periodic = c.periodic;
  Random rng(42);
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<Vec3> pos;
    std::vector<double> rad;
    random_spheres(box, c.particles, rng, pos, rad);
    const double skin = 0.1;
    for (int threads : {1, 2}) {
      std::vector<Vec3> p = pos;
      NeighborList list(skin);
      list.build(box, p, rad, threads);
      const auto expected = brute_force_pairs(box, p, rad, skin);
      const auto got = sorted_pairs(list);
      EXPECT_EQ(got.size(), expected.size()) << c.name << " threads " << threads;
      EXPECT_TRUE(got == expected) << c.name << " threads " << threads;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    Boxes, NeighborListVsBruteForce,
    ::testing::Values(Case{"periodic_cube", {6, 6, 6}, {true, true, true}, 300},
                      Case{"open_cube", {6, 6, 6}, {false, false, false}, 300},
                      Case{"mixed", {5, 7, 6}, {true, false, true}, 300},
                      // edge of 1.2 interaction ranges: one cell per axis, several images
                      Case{"tiny_periodic", {1.25, 1.25, 1.25}, {true, true, true}, 6},
                      Case{"two_cells", {2.5, 2.5, 2.5}, {true, true, true}, 20},
                      Case{"elongated", {1.3, 1.3, 30}, {true, true, true}, 120},
                      Case{"elongated_open", {1.3, 30, 1.3}, {true, false, true}, 120}),
    [](const ::testing::TestParamInfo<Case>& param) { return std::string(param.param.name); });

TEST(NeighborList, RebuildCriterionKeepsEveryContact) {
  // Moving particles by less than half the skin between rebuilds must never lose a pair that
  // came into contact: check against brute force after every move.
  Box box;
  box.length = {6, 6, 6};
  Random rng(7);
  std::vector<Vec3> pos;
  std::vector<double> rad;
  for (int i = 0; i < 200; ++i) {
    pos.push_back({rng.uniform(0, 6), rng.uniform(0, 6), rng.uniform(0, 6)});
    rad.push_back(0.4);
  }
  const double skin = 0.2;
  NeighborList list(skin);
  list.build(box, pos, rad);
  int rebuilds = 0;
  for (int move = 0; move < 60; ++move) {
    for (auto& p : pos) p += 0.01 * rng.unit_vector();
    if (list.needs_rebuild(pos, rad)) {
      list.build(box, pos, rad);
      ++rebuilds;
    }
    // Every touching pair must be in the list (positions are not re-wrapped between
    // rebuilds, so compare through the listed image offsets).
    for (int i = 0; i < 200; ++i)
      for (int j = i + 1; j < 200; ++j) {
        const Vec3 d = box.minimum_image(pos[j] - pos[i]);
        if (norm(d) >= rad[i] + rad[j]) continue;
        bool listed = false;
        for (int p = list.first(i); p < list.first(i + 1); ++p)
          if (list.partner()[p] == j &&
              norm(pos[j] + list.image_offset(list.image()[p]) - pos[i]) < rad[i] + rad[j])
            listed = true;
        ASSERT_TRUE(listed) << "lost pair " << i << "-" << j << " at move " << move;
      }
  }
  EXPECT_GT(rebuilds, 0);
  EXPECT_LT(rebuilds, 60);
}

TEST(NeighborList, PreviousIndexMapsSurvivingPairs) {
  Box box;
  box.length = {5, 5, 5};
  Random rng(3);
  std::vector<Vec3> pos;
  std::vector<double> rad(100, 0.45);
  for (int i = 0; i < 100; ++i) pos.push_back({rng.uniform(0, 5), rng.uniform(0, 5), rng.uniform(0, 5)});
  NeighborList list(0.3);
  list.build(box, pos, rad);
  const std::vector<int> old_partner = list.partner();
  const std::vector<std::uint8_t> old_image = list.image();
  list.build(box, pos, rad);  // same positions: every pair maps onto itself
  ASSERT_EQ(list.pair_count(), old_partner.size());
  for (std::size_t p = 0; p < list.pair_count(); ++p) {
    ASSERT_EQ(list.previous_index()[p], static_cast<int>(p));
  }
}

TEST(NeighborList, RejectsBoxShorterThanInteractionRange) {
  Box box;
  box.length = {0.9, 5, 5};
  std::vector<Vec3> pos{{0.1, 1, 1}};
  std::vector<double> rad{0.5};
  NeighborList list(0.1);
  EXPECT_THROW(list.build(box, pos, rad), InputError);
}

TEST(NeighborList, CoincidentParticlesAreAnInputErrorNotAnAbort) {
  // 10^4 spheres at one point would list 5e7 pairs (10^5 exhausted the memory inside the
  // parallel region): the build stops early and names a crowded particle.
  Box box;
  box.length = {10, 10, 10};
  std::vector<Vec3> pos(10000, Vec3{5, 5, 5});
  std::vector<double> rad(pos.size(), 0.5);
  for (int threads : {1, 2}) {
    NeighborList list(0.1);
    try {
      list.build(box, pos, rad, threads);
      FAIL() << "no error for coincident particles";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("coincident"), std::string::npos) << e.what();
    }
  }
  // A dense but physical packing is untouched by the limit.
  std::vector<Vec3> lattice;
  for (int x = 0; x < 10; ++x)
    for (int y = 0; y < 10; ++y)
      for (int z = 0; z < 10; ++z) lattice.push_back({x + 0.5, y + 0.5, z + 0.5});
  NeighborList list(0.1);
  list.build(box, lattice, std::vector<double>(lattice.size(), 0.5), 2);
  EXPECT_EQ(list.pair_count(), 3u * 10 * 10 * 10);  // periodic: three neighbours per sphere
}
