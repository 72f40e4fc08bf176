#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "../input_error.hpp"
#include "packlab/core/error.hpp"
#include "packlab/generate/fba.hpp"
#include "packlab/generate/opal.hpp"

using namespace packlab;
using namespace packlab::generate;

namespace {

double porosity_of(const Packing& p) {
  double v = 0;
  for (double r : p.radius) v += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  return 1.0 - v / p.box.volume();
}

Box cube(double edge, std::array<bool, 3> periodic = {true, true, true}) {
  Box b;
  b.lo = {-0.3 * edge, 0.1 * edge, 2.0 * edge};  // not at the origin on purpose
  b.length = {edge, edge, edge};
  b.periodic = periodic;
  return b;
}

using test::error_of;

}  // namespace

TEST(Fba, MonodisperseReachesPorosity038WithoutOverlap) {
  Random rng(7);
  FbaParams params;  // target 0.38, tolerance 1e-3
  const auto r = fba_pack(cube(1.0), std::vector<double>(400, 1.0), params, rng);
  EXPECT_EQ(r.status.stop, FbaStop::target_reached);
  EXPECT_NEAR(porosity_of(r.packing), 0.38, 1e-12);
  // Independent brute-force check over every pair and periodic image.
  const double h = brute_force_max_overlap(r.packing);
  EXPECT_LE(h, params.tolerance);
  EXPECT_NEAR(h, r.verified_max_overlap, 1e-12);
  EXPECT_NEAR(h, r.status.max_overlap, 1e-9);
  for (const Vec3& x : r.packing.position)
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(x[a], r.packing.box.lo[a]);
      EXPECT_LT(x[a], r.packing.box.hi()[a]);
    }
}

TEST(Fba, TighterToleranceIsHonoured) {
  Random rng(3);
  FbaParams params;
  params.tolerance = 1e-5;
  const auto r = fba_pack(cube(1.0), std::vector<double>(300, 1.0), params, rng);
  EXPECT_EQ(r.status.stop, FbaStop::target_reached);
  EXPECT_LE(brute_force_max_overlap(r.packing), 1e-5);
}

TEST(Fba, PeriodicOnlyAlongXYWithWallsAlongZ) {
  Random rng(11);
  FbaParams params;
  params.target_porosity = 0.40;
  Box box = cube(1.0, {true, true, false});
  box.length.z = 0.8;
  const auto r = fba_pack(box, std::vector<double>(400, 1.0), params, rng);
  EXPECT_EQ(r.status.stop, FbaStop::target_reached);
  EXPECT_NEAR(porosity_of(r.packing), 0.40, 1e-12);
  EXPECT_LE(brute_force_max_overlap(r.packing), params.tolerance);
  // Whole spheres inside the walls along z; spheres cross the periodic faces along x, y.
  bool crosses_x = false;
  for (std::size_t i = 0; i < r.packing.size(); ++i) {
    const Vec3& x = r.packing.position[i];
    const double R = r.packing.radius[i];
    EXPECT_GE(x.z - R, box.lo.z - 1e-12);
    EXPECT_LE(x.z + R, box.hi().z + 1e-12);
    crosses_x = crosses_x || x.x - R < box.lo.x || x.x + R > box.hi().x;
  }
  EXPECT_TRUE(crosses_x);
}

TEST(Fba, BidisperseSizesKeepTheirRatio) {
  Random rng(5);
  SizeClasses classes;
  classes.sizes = {1.0, 0.6};
  classes.fractions = {0.3, 0.7};
  const auto rho = fba_class_radii(500, classes, rng);
  ASSERT_EQ(rho.size(), 500u);
  long big = 0;
  for (double x : rho) big += x == 0.5 ? 1 : 0;
  EXPECT_EQ(big, 150);
  const auto r = fba_pack(cube(1.0), rho, FbaParams{}, rng);
  EXPECT_EQ(r.status.stop, FbaStop::target_reached);
  EXPECT_NEAR(porosity_of(r.packing), 0.38, 1e-12);
  EXPECT_LE(brute_force_max_overlap(r.packing), 1e-3);
  for (std::size_t i = 0; i < rho.size(); ++i)
    EXPECT_NEAR(r.packing.radius[i] / r.packing.radius[0], rho[i] / rho[0], 1e-12);
}

TEST(Fba, SameSeedSamePackingOtherSeedOther) {
  auto run = [](std::uint64_t seed) {
    Random rng(seed);
    return fba_pack(cube(1.0), std::vector<double>(200, 1.0), FbaParams{}, rng).packing;
  };
  const Packing a = run(42), b = run(42), c = run(43);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a.position[i], b.position[i]);
  EXPECT_NE(a.position[0], c.position[0]);
}

TEST(Fba, HistoryShowsTheOuterScaleShrinkingToTheTarget) {
  Random rng(2);
  const auto r = fba_pack(cube(1.0), std::vector<double>(200, 1.0), FbaParams{}, rng, 10);
  ASSERT_GE(r.history.size(), 2u);
  EXPECT_NEAR(r.history.front().outer_scale, std::cbrt(1.0 / 0.62), 1e-12);
  for (std::size_t k = 1; k < r.history.size(); ++k) {
    EXPECT_LE(r.history[k].outer_scale, r.history[k - 1].outer_scale);
    EXPECT_GE(r.history[k].outer_scale, 1.0);
  }
  EXPECT_LE(r.history.back().max_overlap, 1e-3);
}

TEST(Fba, CountForVolumeFillsToThePorosity) {
  SizeClasses mono;
  const long n = fba_count_for_volume(1000.0, 0.38, 1.0, mono);
  EXPECT_EQ(n, std::lround(0.62 * 1000.0 / (std::numbers::pi / 6.0)));
}

TEST(Fba, BadInputNamesKeyValueAndRange) {
  Random rng(1);
  FbaParams p;
  p.target_porosity = 0.2;
  const std::string m = error_of([&] { fba_pack(cube(1.0), std::vector<double>(10, 1.0), p, rng); });
  EXPECT_NE(m.find("porosity = 0.2"), std::string::npos) << m;
  EXPECT_NE(m.find("[0.3, 1)"), std::string::npos) << m;
  FbaParams q;
  q.tolerance = 0.0;
  EXPECT_NE(error_of([&] { fba_pack(cube(1.0), std::vector<double>(10, 1.0), q, rng); }).find("tolerance"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              fba_pack(cube(1.0), std::vector<double>{1.0, -1.0}, FbaParams{}, rng);
            }).find("relative radius = -1"),
            std::string::npos);
  // Two spheres in a periodic box smaller than their diameter.
  EXPECT_NE(error_of([&] { fba_pack(cube(1.0), std::vector<double>(2, 1.0), FbaParams{}, rng); }).find("box length"),
            std::string::npos);
}

TEST(Fba, RandomPoresDoNotOverlap) {
  Random rng(9);
  Box region = cube(4.0, {true, true, false});
  RandomPores o;
  o.diameter = 1.0;
  o.count = 40;  // pore fraction 40 pi/6 / 64 = 0.33
  const PoreSet pores = random_pores(region, o, rng);
  ASSERT_EQ(pores.size(), 40u);
  Packing p;
  p.box = region;
  for (std::size_t k = 0; k < pores.size(); ++k) {
    EXPECT_EQ(pores.radius[k], 0.5);
    p.add(pores.centre[k], pores.radius[k]);
    EXPECT_GE(pores.centre[k].z, region.lo.z + 0.5 - 1e-12);
    EXPECT_LE(pores.centre[k].z, region.hi().z - 0.5 + 1e-12);
  }
  EXPECT_LE(brute_force_max_overlap(p), 1e-3);
  o.count = 90;  // fraction 0.74
  EXPECT_NE(error_of([&] { random_pores(region, o, rng); }).find("< 0.7"), std::string::npos);
}

// Periodic pores reach the paper's highest porosity, 0.63 (bpm-inverse-opals §4, Fig. 14): the
// pore packing is periodic along z too, and a pore that crosses the open z faces comes back as
// its image at the opposite face, so the region loses exactly the pore volume fraction.
TEST(Fba, PeriodicRandomPoresReachThePapersPorosityAndCutBothFaces) {
  Random rng(5);
  const Box region = cube(4.0, {true, true, false});
  RandomPores o;
  o.diameter = 1.0;
  o.count = 77;  // fraction 77 pi/6 / 64 = 0.630
  o.periodic = true;
  const PoreSet pores = random_pores(region, o, rng);
  ASSERT_GT(pores.size(), 77u);  // some cross a face
  Packing primaries;
  primaries.box = cube(4.0);  // the pore packing itself is periodic along every axis
  for (std::size_t k = 0; k < 77; ++k) {
    EXPECT_GE(pores.centre[k].z, region.lo.z);
    EXPECT_LT(pores.centre[k].z, region.hi().z);
    primaries.add(pores.centre[k], 0.5);
  }
  EXPECT_LE(brute_force_max_overlap(primaries), 1e-3);
  // Each image is a primary shifted by one box length along z, and crosses the face it is near.
  for (std::size_t k = 77; k < pores.size(); ++k) {
    const Vec3& c = pores.centre[k];
    EXPECT_TRUE(c.z < region.lo.z + 0.5 || c.z > region.hi().z - 0.5) << c.z;
    bool found = false;
    for (std::size_t j = 0; j < 77; ++j) {
      const Vec3 d = pores.centre[j] - c;
      found = found || (d.x == 0.0 && d.y == 0.0 && std::abs(std::abs(d.z) - 4.0) < 1e-12);
    }
    EXPECT_TRUE(found) << k;
  }
  // The pore volume inside the region, by a grid (minimum image along x and y only).
  long inside = 0, total = 0;
  const double h = 0.05;
  for (double z = h / 2; z < 4.0; z += h)
    for (double y = h / 2; y < 4.0; y += h)
      for (double x = h / 2; x < 4.0; x += h) {
        ++total;
        const Vec3 point = region.lo + Vec3{x, y, z};
        for (const Vec3& c : pores.centre)
          if (norm(region.minimum_image(c - point)) <= 0.5) {
            ++inside;
            break;
          }
      }
  // 77 pi/6 / 64 = 0.6302; the grid error of 77 spheres of 10 cells per diameter is ~1e-3, and
  // the pores overlap by at most 1e-3 of a diameter.
  EXPECT_NEAR(double(inside) / double(total), 77.0 * std::numbers::pi / 6.0 / 64.0, 4e-3);
}

// A checkpoint is the whole state: stopped after 37 iterations, saved, loaded (with another
// thread count) and run on, the packing is the uninterrupted one bit for bit.
TEST(Fba, SavedAndLoadedRunEqualsTheUninterruptedOne) {
  FbaParams params;
  params.threads = 1;
  const Box box = cube(1.0, {true, true, false});
  const std::vector<double> rho = {1.0, 0.5, 1.0, 0.5, 0.7, 1.0};
  std::vector<double> radii;
  for (int k = 0; k < 50; ++k) radii.insert(radii.end(), rho.begin(), rho.end());
  Random rng_straight(11);
  const FbaResult straight = fba_pack(box, radii, params, rng_straight, 5);
  ASSERT_GT(straight.status.iteration, 60);

  Random rng(11);
  FbaRun first(box, radii, params, rng, 5);
  EXPECT_FALSE(first.run(37));
  std::stringstream saved;
  first.save_state(saved);
  FbaRun second = FbaRun::load_state(saved, 2);
  EXPECT_TRUE(second.run());
  const FbaResult resumed = second.result();
  EXPECT_EQ(resumed.packing.position, straight.packing.position);
  EXPECT_EQ(resumed.status.iteration, straight.status.iteration);
  EXPECT_EQ(resumed.status.max_overlap, straight.status.max_overlap);
  ASSERT_EQ(resumed.history.size(), straight.history.size());
  for (std::size_t k = 0; k < straight.history.size(); ++k)
    EXPECT_EQ(resumed.history[k].outer_scale, straight.history[k].outer_scale) << k;
}
