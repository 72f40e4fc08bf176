// Least-squares fits: exact recovery of linear regression (closed-form OLS and its standard
// errors), recovery of eq. 6 from noisy synthetic data with standard errors that match the
// scatter over replicates, and the sandwich errors for an empirical distribution function.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "packlab/analyze/fits.hpp"
#include "packlab/core/error.hpp"

namespace packlab::analyze {
namespace {

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

double sd(const std::vector<double>& v) {
  const double m = mean(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / static_cast<double>(v.size() - 1));
}

TEST(Fits, LinearModelGivesClosedFormOrdinaryLeastSquares) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.3);
  std::vector<double> x, y;
  for (int i = 0; i < 25; ++i) {
    x.push_back(0.4 * i);
    y.push_back(1.5 - 2.0 * x.back() + noise(rng));
  }
  const FitModel line = [](double xi, const std::vector<double>& p, std::vector<double>* g) {
    if (g) *g = {1.0, xi};
    return p[0] + p[1] * xi;
  };
  const FitResult r = fit_least_squares(line, x, y, {0.0, 0.0});
  // Closed form: slope = Sxy/Sxx, intercept = ybar - slope xbar, se(slope) = s/sqrt(Sxx),
  // se(intercept) = s sqrt(1/n + xbar^2/Sxx), s^2 = RSS/(n-2).
  const double n = static_cast<double>(x.size()), xb = mean(x), yb = mean(y);
  double sxx = 0, sxy = 0, tss = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxx += (x[i] - xb) * (x[i] - xb);
    sxy += (x[i] - xb) * (y[i] - yb);
    tss += (y[i] - yb) * (y[i] - yb);
  }
  const double slope = sxy / sxx, intercept = yb - slope * xb;
  double rss = 0;
  for (std::size_t i = 0; i < x.size(); ++i) rss += std::pow(y[i] - intercept - slope * x[i], 2);
  const double s = std::sqrt(rss / (n - 2));
  EXPECT_TRUE(r.converged) << r.status;
  EXPECT_NEAR(r.params[1], slope, 1e-9 * std::abs(slope));
  EXPECT_NEAR(r.params[0], intercept, 1e-9 * std::abs(intercept));
  EXPECT_NEAR(r.std_errors[1], s / std::sqrt(sxx), 1e-9 * s / std::sqrt(sxx));
  EXPECT_NEAR(r.std_errors[0], s * std::sqrt(1 / n + xb * xb / sxx), 1e-9);
  EXPECT_NEAR(r.r2, 1.0 - rss / tss, 1e-12);
  EXPECT_EQ(r.points, 25);
}

TEST(Fits, ErfFitRecoversExactDataWithoutNoise) {
  std::vector<double> x, p;
  for (int i = 0; i <= 80; ++i) {
    x.push_back(0.03 * i);
    p.push_back(pore_erf_model(x.back(), 0.47, 0.21));
  }
  const ErfFit f = fit_pore_erf(x, p);
  EXPECT_TRUE(f.converged);
  EXPECT_NEAR(f.a, 0.47, 1e-9);
  EXPECT_NEAR(f.b, 0.21, 1e-9);
  EXPECT_NEAR(f.r2, 1.0, 1e-15);
}

TEST(Fits, ErfFitStandardErrorsMatchTheScatterOverReplicates) {
  // 400 replicates of eq. 6 (a = 0.45, b = 0.30) plus independent N(0, 0.01) noise: the mean
  // estimate is unbiased and the reported standard error equals the observed scatter.
  const double a = 0.45, b = 0.30, sigma = 0.01;
  std::mt19937_64 rng(2024);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<double> as, bs, a_errs, b_errs;
  for (int rep = 0; rep < 400; ++rep) {
    std::vector<double> x, p;
    for (int i = 0; i < 60; ++i) {
      x.push_back(2.5 * i / 59.0);
      p.push_back(pore_erf_model(x.back(), a, b) + noise(rng));
    }
    const ErfFit f = fit_pore_erf(x, p);
    ASSERT_TRUE(f.converged);
    as.push_back(f.a);
    bs.push_back(f.b);
    a_errs.push_back(f.a_err);
    b_errs.push_back(f.b_err);
    EXPECT_EQ(f.a_err, f.a_ls_err);  // no data covariance: the textbook errors
  }
  // Standard error of the mean over 400 replicates: sd/20; allow 4 of them.
  EXPECT_NEAR(mean(as), a, 4 * sd(as) / 20);
  EXPECT_NEAR(mean(bs), b, 4 * sd(bs) / 20);
  // The sample sd of 400 values is known to about 1/sqrt(800) = 3.5 %: allow 12 %.
  EXPECT_NEAR(mean(a_errs) / sd(as), 1.0, 0.12);
  EXPECT_NEAR(mean(b_errs) / sd(bs), 1.0, 0.12);
}

TEST(Fits, SandwichErrorsOfAnEmpiricalDistributionMatchTheScatter) {
  // Distances drawn from |N(0, a^2)| have P(r > x) = 1 - erf(x / (a sqrt 2)): eq. 6 with b = 0.
  // The empirical P at different x is correlated; the sandwich errors account for it, the
  // textbook errors do not (they come out several times too small).
  const double a = 0.35;
  const int n = 4000, grid = 60, reps = 300;
  std::mt19937_64 rng(99);
  std::normal_distribution<double> normal(0.0, a);
  std::vector<double> as, a_errs, a_ls;
  std::vector<double> x(grid);
  for (int k = 0; k < grid; ++k) x[k] = 3.0 * a * k / (grid - 1);
  for (int rep = 0; rep < reps; ++rep) {
    std::vector<double> d(n);
    for (double& v : d) v = std::abs(normal(rng));
    std::sort(d.begin(), d.end());
    std::vector<double> p(grid);
    for (int k = 0; k < grid; ++k) p[k] = static_cast<double>(d.end() - std::upper_bound(d.begin(), d.end(), x[k])) / n;
    std::vector<std::vector<double>> cov(grid, std::vector<double>(grid));
    for (int i = 0; i < grid; ++i)
      for (int k = 0; k < grid; ++k) cov[i][k] = (p[std::max(i, k)] - p[i] * p[k]) / n;
    const ErfFit f = fit_pore_erf(x, p, &cov);
    ASSERT_TRUE(f.converged);
    as.push_back(f.a);
    a_errs.push_back(f.a_err);
    a_ls.push_back(f.a_ls_err);
  }
  EXPECT_NEAR(mean(as), a, 4 * sd(as) / std::sqrt(static_cast<double>(reps)));
  EXPECT_NEAR(mean(a_errs) / sd(as), 1.0, 0.15);
  EXPECT_LT(mean(a_ls) / sd(as), 0.6);
}

TEST(Fits, RejectsUnusableData) {
  const FitModel constant = [](double, const std::vector<double>& p, std::vector<double>* g) {
    if (g) *g = {1.0};
    return p[0];
  };
  EXPECT_THROW(fit_least_squares(constant, {1, 2, 3}, {1, 2}, {0.0}), InputError);
  EXPECT_THROW(fit_least_squares(constant, {1}, {1}, {0.0}), InputError);
  EXPECT_THROW(fit_least_squares(constant, {1, 2}, {1, std::nan("")}, {0.0}), InputError);
}

}  // namespace
}  // namespace packlab::analyze
