// Pore-size distribution: the nearest-surface query against brute force (periodic, open,
// overlapping, polydisperse), the analytic P(r_P > r) of one sphere in a periodic cube,
// the porosity of two overlapping spheres, thread independence, accumulation, the sample
// size rule and the degree-of-heterogeneity fit's invariance under a change of unit.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>

#include "packlab/analyze/pore_size.hpp"
#include "packlab/core/error.hpp"
#include "packlab/generate/random.hpp"

namespace packlab::analyze {
namespace {

constexpr double pi = std::numbers::pi;

double brute_force_distance(const Packing& p, const Vec3& x) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i)
    for (int sx = -1; sx <= 1; ++sx)
      for (int sy = -1; sy <= 1; ++sy)
        for (int sz = -1; sz <= 1; ++sz) {
          const int s[3] = {sx, sy, sz};
          Vec3 c = p.position[i];
          bool skip = false;
          for (int a = 0; a < 3; ++a) {
            if (s[a] != 0 && !p.box.periodic[a]) skip = true;
            c[a] += s[a] * p.box.length[a];
          }
          if (!skip) best = std::min(best, norm(x - c) - p.radius[i]);
        }
  return std::max(0.0, best);
}

TEST(PoreSize, NearestSurfaceMatchesBruteForce) {
  // Overlapping polydisperse spheres; periodic, mixed and open boxes.
  for (const auto periodic : {std::array<bool, 3>{true, true, true}, std::array<bool, 3>{true, false, true},
                              std::array<bool, 3>{false, false, false}}) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Packing p;
    p.box.lo = {-2.0, 1.0, 0.5};
    p.box.length = {9.0, 7.0, 8.0};
    p.box.periodic = periodic;
    for (int i = 0; i < 300; ++i)
      p.add({p.box.lo.x + 9.0 * u(rng), p.box.lo.y + 7.0 * u(rng), p.box.lo.z + 8.0 * u(rng)}, 0.2 + 0.5 * u(rng));
    const SurfaceDistance distance(p);
    int inside = 0;
    for (int k = 0; k < 3000; ++k) {
      const Vec3 x{p.box.lo.x + 9.0 * u(rng), p.box.lo.y + 7.0 * u(rng), p.box.lo.z + 8.0 * u(rng)};
      const double expected = brute_force_distance(p, x);
      ASSERT_NEAR(distance(x), expected, 1e-12) << "point " << k;
      inside += expected == 0.0;
    }
    EXPECT_GT(inside, 100);  // both branches exercised
    EXPECT_LT(inside, 2900);
  }
}

// One sphere of radius R in a periodic cube of edge L (any position: images matter when it
// sits in a corner): for R + r <= L/2 the points farther than R + r from the centre fill
// L^3 - 4/3 pi (R + r)^3.
Packing single_sphere(double L, double R, Vec3 centre) {
  Packing p;
  p.box.length = {L, L, L};
  p.add(centre, R);
  return p;
}

TEST(PoreSize, SingleSphereInPeriodicCubeIsAnalytic) {
  const double L = 4.0, R = 1.0;
  const Packing p = single_sphere(L, R, {0.2, 3.9, 2.0});
  PoreSizeParams params;
  params.points = 200000;
  PoreSize pores(params);
  Random rng(5);
  pores.compute(p, rng);
  const double n = static_cast<double>(pores.counted_points());
  EXPECT_EQ(pores.counted_points(), 200000);
  const double solid = 4.0 / 3.0 * pi * R * R * R, cube = L * L * L;
  const double porosity = 1.0 - solid / cube;
  EXPECT_NEAR(pores.porosity(), porosity, 4 * pores.porosity_std_error());
  for (double r : {0.0, 0.1, 0.3, 0.5, 0.8, 1.0}) {
    const double exact = (cube - 4.0 / 3.0 * pi * std::pow(R + r, 3)) / (cube - solid);
    const double se = std::sqrt(exact * (1 - exact) / n);
    EXPECT_NEAR(pores.probability(r), exact, 4 * se + 1e-15) << "r = " << r;
    // and the uniform band holds the exact curve
    EXPECT_LE(std::abs(pores.probability(r) - exact), pores.band());
  }
  // No point is farther than the cube's half-diagonal minus R.
  EXPECT_LE(pores.distances().back(), std::sqrt(3.0) * L / 2 - R + 1e-12);
  EXPECT_GT(pores.distances().back(), std::sqrt(3.0) * L / 2 - R - 0.2);
}

TEST(PoreSize, AllPointsDefinitionStartsAtThePorosity) {
  const double L = 4.0, R = 1.0;
  PoreSizeParams params;
  params.points = 100000;
  params.definition = PoreDefinition::all_points;
  PoreSize pores(params);
  Random rng(6);
  pores.compute(single_sphere(L, R, {2, 2, 2}), rng);
  EXPECT_EQ(pores.drawn_points(), pores.counted_points());
  EXPECT_DOUBLE_EQ(pores.probability(0.0), pores.porosity());
  const double r = 0.4, exact = 1.0 - 4.0 / 3.0 * pi * std::pow(R + r, 3) / (L * L * L);
  EXPECT_NEAR(pores.probability(r), exact, 4 * std::sqrt(exact * (1 - exact) / 1e5));
  EXPECT_THROW((void)fit_degree_of_heterogeneity(pores), InputError);
}

TEST(PoreSize, OverlappingSpheresCountTheirUnionOnce) {
  // Two spheres of radius R at distance d < 2R: solid volume 2 V - lens, lens =
  // pi (4R + d)(2R - d)^2 / 12. No hard-sphere assumption anywhere.
  const double L = 5.0, R = 1.0, d = 0.8;
  Packing p;
  p.box.length = {L, L, L};
  p.add({2.5 - d / 2, 2.5, 2.5}, R);
  p.add({2.5 + d / 2, 2.5, 2.5}, R);
  PoreSizeParams params;
  params.points = 200000;
  PoreSize pores(params);
  Random rng(8);
  pores.compute(p, rng);
  const double lens = pi * (4 * R + d) * (2 * R - d) * (2 * R - d) / 12.0;
  const double solid = 2 * 4.0 / 3.0 * pi * R * R * R - lens;
  EXPECT_NEAR(pores.porosity(), 1.0 - solid / (L * L * L), 4 * pores.porosity_std_error());
  // The nominal volume fraction counts the lens twice: a different (wrong) porosity.
  EXPECT_GT(std::abs(pores.porosity() - (1.0 - p.volume_fraction())), 10 * pores.porosity_std_error());
}

Packing random_overlapping(long n, std::uint64_t seed) {
  generate::RandomPackingParams rp;
  rp.particles = n;
  rp.volume_fraction = 0.45;
  Random rng(seed);
  return generate::make_random_packing(rp, rng);
}

TEST(PoreSize, ResultDoesNotDependOnTheThreadCount) {
  const Packing p = random_overlapping(2000, 3);
  std::vector<double> reference;
  for (int threads : {1, 2, 3}) {
    PoreSizeParams params;
    params.points = 30000;
    params.threads = threads;
    PoreSize pores(params);
    Random rng(42);
    pores.compute(p, rng);
    if (reference.empty()) {
      reference = pores.distances();
    } else {
      EXPECT_EQ(pores.distances(), reference) << threads << " threads";
    }
  }
}

TEST(PoreSize, RealizationsArePooledWithEqualWeight) {
  const Packing a = random_overlapping(500, 1), b = random_overlapping(500, 2);
  PoreSizeParams params;
  params.points = 5000;
  PoreSize pores(params);
  Random rng(1);
  pores.compute(a, rng);
  pores.compute(b, rng, /*reset=*/false);
  ASSERT_EQ(pores.frames(), 2);
  EXPECT_EQ(pores.counted_points(), 10000);
  for (double r : {0.0, 0.05, 0.1, 0.2, 0.4})
    EXPECT_NEAR(pores.probability(r), 0.5 * (pores.probability(r, 0) + pores.probability(r, 1)), 1e-15);
  EXPECT_EQ(pores.drawn_points(), pores.drawn_points(0) + pores.drawn_points(1));
}

TEST(PoreSize, SampleSizeFollowsTheConfidenceBand) {
  const long n = points_for_band(0.005, 0.95);
  EXPECT_LE(band_for_points(n, 0.95), 0.005);
  EXPECT_GT(band_for_points(n - 1, 0.95), 0.005);
  EXPECT_EQ(PoreSize(PoreSizeParams{}).target_points(), n);
  EXPECT_THROW((void)points_for_band(0.0, 0.95), InputError);
}

TEST(PoreSize, OpenWallsKeepTheirMargin) {
  Packing p = random_overlapping(400, 4);
  p.box.periodic = {false, false, false};
  PoreSizeParams params;
  params.points = 2000;
  params.wall_margin = 0.5 * p.box.length.x;  // nothing left to sample
  Random first(1);
  EXPECT_THROW(PoreSize(params).compute(p, first), InputError);
  params.wall_margin = 1.0;
  PoreSize pores(params);
  Random rng(2);
  pores.compute(p, rng);
  EXPECT_EQ(pores.counted_points(), 2000);
}

TEST(PoreSize, DegreeOfHeterogeneityDoesNotDependOnTheUnit) {
  // The same packing in metres and in micrometres: eq. 6 is fitted in r/r0, so a and b agree;
  // the tabulated r scales with the unit.
  const Packing p = random_overlapping(3000, 9);
  Packing q = p;
  const double scale = 1e-6;
  q.box.length = q.box.length * scale;
  for (auto& x : q.position) x = x * scale;
  for (auto& r : q.radius) r *= scale;
  PoreSizeParams params;
  params.points = 20000;
  PoreSize pp(params), pq(params);
  Random r1(3), r2(3);
  pp.compute(p, r1);
  pq.compute(q, r2);
  const DohFit fp = fit_degree_of_heterogeneity(pp), fq = fit_degree_of_heterogeneity(pq);
  EXPECT_TRUE(fp.fit.converged);
  EXPECT_NEAR(fq.fit.a, fp.fit.a, 1e-6 * fp.fit.a);
  EXPECT_NEAR(fq.fit.b, fp.fit.b, 1e-6 * std::abs(fp.fit.a));
  EXPECT_NEAR(fq.r0, fp.r0 * scale, 1e-12 * fq.r0);
  EXPECT_NEAR(pq.curve(11).r.back(), pp.curve(11).r.back() * scale, 1e-9 * pq.curve(11).r.back());
  EXPECT_GT(fp.fit.r2, 0.9);
  EXPECT_GT(fp.fit.a_err, 0.0);
}

TEST(PoreSize, ReadingBeforeComputingIsALogicError) {
  PoreSize pores;
  EXPECT_THROW((void)pores.distances(), std::logic_error);
  EXPECT_THROW((void)pores.porosity(), std::logic_error);
}

}  // namespace
}  // namespace packlab::analyze
