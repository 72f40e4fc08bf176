// RDF estimation against lattices with exact shell counts, the ideal gas (g = 1) with each edge
// correction, and the analytic reference RDFs against their closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "packlab/analyze/rdf.hpp"
#include "packlab/analyze/reference_rdf.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/random.hpp"
#include "packlab/generate/lattice.hpp"

using namespace packlab;

namespace {

Packing sc_lattice(int cells, double radius = 1.0) {
  generate::LatticeParams lp;
  lp.type = generate::LatticeType::sc;
  lp.cells = {cells, cells, cells};
  lp.radius = radius;
  return generate::make_lattice(lp);
}

std::size_t bin_of(double r, double dr) { return static_cast<std::size_t>(std::lround(r / dr)) - 1; }

Packing poisson(long n, double edge, bool periodic, std::uint64_t seed) {
  Random rng(seed);
  Packing p;
  p.box.length = {edge, edge, edge};
  p.box.periodic = {periodic, periodic, periodic};
  for (long i = 0; i < n; ++i) p.add({rng.uniform(0, edge), rng.uniform(0, edge), rng.uniform(0, edge)}, 1.0);
  return p;
}

double mean_g(const analyze::Rdf& rdf, double from, double to) {
  const auto r = rdf.reduced_r();
  const auto g = rdf.g();
  double s = 0;
  int c = 0;
  for (std::size_t b = 0; b < r.size(); ++b)
    if (r[b] >= from && r[b] <= to) {
      s += g[b];
      ++c;
    }
  return s / c;
}

}  // namespace

TEST(Rdf, ShellCountOfSimpleCubicLatticeIsSixAtTwoRadiiForAnyBinWidth) {
  // Paper §4.1 / Fig. 7: I(2a) = 6 for dR = 0.1 ... 0.003 while g+(2, dR) = 9.55, 95.5, 190.9, 318.
  const Packing sc = sc_lattice(5);
  const double drs[] = {0.1, 0.01, 0.005, 0.003};
  const double paper[] = {9.55, 95.5, 190.9, 318.0};
  for (int q = 0; q < 4; ++q) {
    analyze::RdfParams p;
    p.dr = drs[q];
    p.r_max = 4.5;
    analyze::Rdf rdf(p);
    rdf.compute(sc);
    const auto I = rdf.shell_count();
    EXPECT_DOUBLE_EQ(I[bin_of(2.0, p.dr)], 6.0) << "dR = " << p.dr;
    EXPECT_DOUBLE_EQ(I[bin_of(2.0 * std::sqrt(2.0), p.dr)], 12.0) << "dR = " << p.dr;
    EXPECT_DOUBLE_EQ(I[bin_of(4.0, p.dr)], 6.0) << "dR = " << p.dr;
    double total = 0;
    for (double v : I) total += v;
    // Neighbours within R = 4.5: 6 at 2, 12 at 2.83, 8 at 3.46, 6 at 4, 24 at 4.47.
    EXPECT_DOUBLE_EQ(total, 6.0 + 12.0 + 8.0 + 6.0 + 24.0);
    EXPECT_NEAR(rdf.contact_value(0, 0), paper[q], 1.5e-3 * paper[q]) << "dR = " << p.dr;
    EXPECT_NEAR(rdf.contact_value(0, 0), 6.0 / (2 * std::numbers::pi * p.dr), 1e-9);
  }
}

TEST(Rdf, PeriodicImagesBeyondHalfTheBoxCount) {
  // 2 x 2 x 2 SC cells (edge 4a): at R = 4 the six neighbours are images of the particle's own
  // neighbours; toroidal correction counts every image.
  analyze::RdfParams p;
  p.dr = 0.01;
  p.r_max = 6.0;
  analyze::Rdf rdf(p);
  rdf.compute(sc_lattice(2));
  const auto I = rdf.shell_count();
  EXPECT_DOUBLE_EQ(I[bin_of(2.0, p.dr)], 6.0);
  EXPECT_DOUBLE_EQ(I[bin_of(4.0, p.dr)], 6.0);
  EXPECT_DOUBLE_EQ(I[bin_of(4.0 * std::sqrt(2.0), p.dr)], 12.0);
}

TEST(Rdf, FccShellsAndWindowHistogram) {
  generate::LatticeParams lp;
  lp.type = generate::LatticeType::fcc;
  lp.cells = {3, 3, 3};
  analyze::RdfParams p;
  p.dr = 0.02;
  p.r_max = 3.0;
  p.window_radius = 2.5;
  analyze::Rdf rdf(p);
  rdf.compute(generate::make_lattice(lp));  // radius 0.5: a = 0.5, neighbours at R = 2, 2 sqrt 2
  const auto I = rdf.shell_count();
  EXPECT_DOUBLE_EQ(I[bin_of(2.0, p.dr)], 12.0);
  EXPECT_DOUBLE_EQ(I[bin_of(2.0 * std::sqrt(2.0), p.dr)], 6.0);
  const auto h = rdf.window_histogram();
  ASSERT_EQ(h.size(), 13u);
  EXPECT_DOUBLE_EQ(h[12], 1.0);  // every window of radius 2.5a holds the 12 nearest neighbours
}

TEST(Rdf, IdealGasIsOneWithEveryEdgeCorrection) {
  analyze::RdfParams p;
  p.dr = 0.25;
  p.r_max = 6.0;
  {
    analyze::Rdf rdf(p);
    for (std::uint64_t s = 1; s <= 3; ++s) rdf.accumulate(poisson(3000, 30.0, true, s));
    EXPECT_EQ(rdf.realizations(), 3);
    EXPECT_NEAR(mean_g(rdf, 1.0, 6.0), 1.0, 0.01);
    const auto K = rdf.k_function();
    const double r = 6.0 + 0.5 * p.dr;
    EXPECT_NEAR(K.back(), 4.0 / 3.0 * std::numbers::pi * r * r * r, 0.01 * K.back());
  }
  for (const char* edge : {"ripley", "minus-sampling"}) {
    p.edge = analyze::edge_correction_from_name(edge);
    analyze::Rdf rdf(p);
    for (std::uint64_t s = 1; s <= 3; ++s) rdf.accumulate(poisson(3000, 30.0, false, s));
    EXPECT_NEAR(mean_g(rdf, 1.0, 6.0), 1.0, 0.02) << edge;
    EXPECT_NEAR(mean_g(rdf, 4.0, 6.0), 1.0, 0.03) << edge;
  }
  // Without a correction an open box would lose the neighbours beyond the faces: the weights
  // matter. Check them directly: a sphere centred on a face, an edge and a corner.
  Box box;
  box.length = {10, 10, 10};
  box.periodic = {false, false, false};
  EXPECT_NEAR(analyze::sphere_fraction_in_box(box, {5, 5, 5}, 2.0), 1.0, 0);
  EXPECT_NEAR(analyze::sphere_fraction_in_box(box, {0, 5, 5}, 2.0), 0.5, 1e-12);
  EXPECT_NEAR(analyze::sphere_fraction_in_box(box, {0, 0, 5}, 2.0), 0.25, 1e-12);
  EXPECT_NEAR(analyze::sphere_fraction_in_box(box, {0, 0, 0}, 2.0), 0.125, 1e-12);
  // One face at distance d: the cap beyond it holds (1 - d/r)/2 of the surface.
  EXPECT_NEAR(analyze::sphere_fraction_in_box(box, {0.5, 5, 5}, 2.0), 1.0 - (1.0 - 0.25) / 2.0, 1e-7);  // quadrature
  // Two faces at distances 0.5 and 1 (edge region, caps overlap): against Monte Carlo.
  Random rng(1);
  long inside = 0;
  const long samples = 400000;
  for (long s = 0; s < samples; ++s) {
    const Vec3 q = Vec3{0.5, 1.0, 5} + rng.unit_vector() * 2.0;
    inside += q.x >= 0 && q.y >= 0;
  }
  EXPECT_NEAR(analyze::sphere_fraction_in_box(box, {0.5, 1.0, 5}, 2.0), static_cast<double>(inside) / samples, 3e-3);
}

TEST(Rdf, PartialRdfsOfATwoClassLattice) {
  // SC lattice of spacing 1 whose classes alternate (radii 0.5 and 0.4, a rock-salt pattern):
  // every sphere has 6 unlike neighbours at 1 and 12 like ones at sqrt 2.
  Packing p = sc_lattice(6, 0.5);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto& x = p.position[i];
    const long s = std::lround(x.x - 0.5) + std::lround(x.y - 0.5) + std::lround(x.z - 0.5);
    if (s % 2) p.radius[i] = 0.4;
  }
  analyze::RdfParams rp;
  rp.dr = 0.01;
  rp.r_max = 4.0;
  analyze::Rdf rdf(rp);
  rdf.compute(p);
  ASSERT_EQ(rdf.classes(), 2);
  EXPECT_DOUBLE_EQ(rdf.class_radius()[1], 0.4);
  // R in units of a = 0.5: r = 1 -> R = 2, r = sqrt 2 -> R = 2.83.
  EXPECT_DOUBLE_EQ(rdf.shell_count(0, 1)[bin_of(2.0, rp.dr)], 6.0);
  EXPECT_DOUBLE_EQ(rdf.shell_count(1, 0)[bin_of(2.0, rp.dr)], 6.0);
  EXPECT_DOUBLE_EQ(rdf.shell_count(0, 0)[bin_of(2.0, rp.dr)], 0.0);
  EXPECT_DOUBLE_EQ(rdf.shell_count(0, 0)[bin_of(2.0 * std::sqrt(2.0), rp.dr)], 12.0);
  EXPECT_DOUBLE_EQ(rdf.shell_count(1, 1)[bin_of(2.0 * std::sqrt(2.0), rp.dr)], 12.0);
  // Symmetry g_km = g_mk and the total as the number-weighted mix.
  const auto g01 = rdf.g(0, 1), g10 = rdf.g(1, 0);
  for (std::size_t b = 0; b < g01.size(); ++b) ASSERT_NEAR(g01[b], g10[b], 1e-9 * (1 + g01[b]));
  EXPECT_DOUBLE_EQ(rdf.shell_count()[bin_of(2.0, rp.dr)], 6.0);
}

TEST(Rdf, AveragingIsTheMeanOfTheRealizations) {
  analyze::RdfParams p;
  p.dr = 0.1;
  p.r_max = 5.0;
  analyze::Rdf a(p), b(p), both(p), merged(p);
  const Packing p1 = poisson(500, 12.0, true, 1), p2 = poisson(500, 12.0, true, 2);
  a.compute(p1);
  b.compute(p2);
  both.accumulate(p1);
  both.accumulate(p2);
  merged.add(a);
  merged.add(b);
  const auto ga = a.g(), gb = b.g(), g2 = both.g(), gm = merged.g();
  for (std::size_t k = 0; k < ga.size(); ++k) {
    ASSERT_NEAR(g2[k], 0.5 * (ga[k] + gb[k]), 1e-12);
    ASSERT_NEAR(gm[k], g2[k], 1e-12);
  }
}

TEST(Rdf, ReadingBeforeComputingIsAnError) {
  analyze::Rdf rdf;
  EXPECT_THROW((void)rdf.g(), std::logic_error);
  analyze::RdfParams p;
  p.dr = 0;
  EXPECT_THROW(analyze::Rdf{p}, InputError);
  EXPECT_THROW(analyze::edge_correction_from_name("mirror"), InputError);
}

TEST(ReferenceRdf, PercusYevickContactValuesAndWillis) {
  namespace ref = analyze::reference;
  for (double c : {0.1, 0.3, 0.575, 0.6}) {
    const double py = (1 + c / 2) / ((1 - c) * (1 - c));
    EXPECT_DOUBLE_EQ(ref::percus_yevick_contact(c), py);
    // One class as a "mixture", and two classes of equal size.
    EXPECT_NEAR(ref::percus_yevick_contact_mixture({0.5}, {c})[0][0], py, 1e-12);
    const auto g2 = ref::percus_yevick_contact_mixture({0.5, 0.5}, {0.3 * c, 0.7 * c});
    for (const auto& row : g2)
      for (double v : row) EXPECT_NEAR(v, py, 1e-12);
    // Eq. (23): class 2 infinitely dilute in class 1 (size ratio 0.313).
    const auto gd = ref::percus_yevick_contact_mixture({1.0, 0.313}, {c, 1e-14});
    EXPECT_NEAR(gd[0][1], ref::percus_yevick_contact_dilute(c, 0.313), 1e-9);
    EXPECT_NEAR(gd[0][1], gd[1][0], 1e-12);
    // Eq. (21): g_ij = (a_j g_ii + a_i g_jj) / (a_i + a_j) with radii a.
    const auto gm = ref::percus_yevick_contact_mixture({1.0, 0.313}, {0.75 * c, 0.25 * c});
    EXPECT_NEAR(gm[0][1], (0.313 * gm[0][0] + 1.0 * gm[1][1]) / 1.313, 1e-12);
    // Willis (Kanaun): contact value = PY; well-stirred step.
    EXPECT_NEAR(ref::willis(2.0, 1.0, c), py, 1e-12);
    EXPECT_EQ(ref::willis(1.99, 1.0, c), 0.0);
    EXPECT_NEAR(ref::willis(30.0, 1.0, c), 1.0, 1e-9);
  }
  EXPECT_EQ(ref::well_stirred(1.999, 1.0), 0.0);
  EXPECT_EQ(ref::well_stirred(2.0, 1.0), 1.0);
  EXPECT_NEAR(ref::percus_yevick_contact_dilute(0.6, 1.0), (1 + 0.3) / 0.16, 1e-12);
  EXPECT_THROW(ref::willis_contact_original(0.1), InputError);
}

// The full Percus-Yevick g(r) (Wertheim's solution by Ornstein-Zernike in Fourier space): the
// exact solution has h = -1 inside the core and g(2a+) = (1 + c/2) / (1 - c)^2; the numbers must
// give both (the core is not imposed: h there comes out of the transform), and g -> 1 far away.
TEST(ReferenceRdf, PercusYevickFullCurveHasTheExactCoreAndContactValue) {
  namespace ref = analyze::reference;
  const std::vector<double> core{1.0, 1.5, 1.9, 1.99};
  for (double c : {0.1, 0.3, 0.5, 0.6}) {
    for (double h : ref::percus_yevick_total_correlation(core, c)) EXPECT_NEAR(h, -1.0, 1e-4) << "c = " << c;
    const std::vector<double> g = ref::percus_yevick({1.0, 2.0, 30.0}, c);
    EXPECT_EQ(g[0], 0.0);
    EXPECT_NEAR(g[1], ref::percus_yevick_contact(c), 1e-6 * ref::percus_yevick_contact(c)) << "c = " << c;
    // Far away (15 diameters): 1, except at c = 0.6, beyond freezing, where the shells persist.
    if (c <= 0.5) {
      EXPECT_NEAR(g[2], 1.0, 2e-3) << "c = " << c;
    }
  }
  // Dilute: g = 1 outside the core to first order in c (h = c-independent Mayer term only inside).
  for (double g : ref::percus_yevick({2.0, 2.5, 4.0, 8.0}, 1e-4)) EXPECT_NEAR(g, 1.0, 1e-3);
  // c = 0.5: the first minimum lies below 1 and the second peak above it (the liquid's shells).
  const std::vector<double> shells = ref::percus_yevick({3.0, 4.0}, 0.5);
  EXPECT_LT(shells[0], 0.7);
  EXPECT_GT(shells[1], 1.2);
  EXPECT_THROW(ref::percus_yevick({2.0}, 1.0), InputError);
  EXPECT_THROW(ref::percus_yevick({0.0}, 0.3), InputError);
}
