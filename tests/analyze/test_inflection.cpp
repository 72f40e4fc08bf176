// Inflection point of a step curve (logistic fit) and the power law above it (eq. 5, 9).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "packlab/analyze/inflection.hpp"
#include "packlab/analyze/power_law.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/random.hpp"

using namespace packlab;
using namespace packlab::analyze;

namespace {

struct Step {
  double a = 0.8, b = 0.4, c = 3.0, x0 = 1.03, w = 0.02;
  double operator()(double x) const { return a + b * (x - x0) + c / (1.0 + std::exp(-(x - x0) / w)); }
  double y0() const { return a + 0.5 * c; }
  double slope() const { return b + c / (4.0 * w); }
};

// q from 0.005 in steps of 0.005 (the VEM grid) up to `q_max`.
std::vector<double> vem_grid(double q_max) {
  std::vector<double> q;
  for (int k = 1; 0.005 * k <= q_max + 1e-12; ++k) q.push_back(0.005 * k);
  return q;
}

}  // namespace

TEST(Inflection, TotalVolumeFractionIsEquationFive) {
  EXPECT_DOUBLE_EQ(total_volume_fraction(0.4, 1.0, 0.5), 0.6);
  EXPECT_DOUBLE_EQ(total_volume_fraction(0.4, 0.0, 0.5), 0.4);
  // q_i n^(1/3) = 0.82 (eq. 4) gives Phi_T,i = Phi_S (1 + 0.82^3) for any n.
  for (double n : {0.05, 0.25, 1.0, 2.0})
    EXPECT_NEAR(total_volume_fraction(0.4, 0.82 / std::cbrt(n), n), 0.4 * (1.0 + 0.82 * 0.82 * 0.82), 1e-14);
  Inflection inf;
  inf.x = 1.2;
  inf.x_err = 0.01;
  const auto phi = inflection_volume_fraction(0.3, 0.5, inf);
  EXPECT_DOUBLE_EQ(phi.value, 0.3 * (1.0 + 0.5 * 1.2 * 1.2 * 1.2));
  EXPECT_DOUBLE_EQ(phi.err, 3.0 * 0.3 * 0.5 * 1.2 * 1.2 * 0.01);
}

TEST(Inflection, ExactLogisticStepIsRecovered) {
  const Step s;
  const std::vector<double> x = vem_grid(1.3);
  std::vector<double> y;
  for (double q : x) y.push_back(s(q));
  const Inflection inf = find_inflection(x, y);
  ASSERT_TRUE(inf.found) << inf.message;
  EXPECT_NEAR(inf.x, s.x0, 1e-9);
  EXPECT_NEAR(inf.y, s.y0(), 1e-9);
  EXPECT_NEAR(inf.slope, s.slope(), 1e-7);
  EXPECT_NEAR(inf.width, s.w, 1e-9);
  EXPECT_GT(inf.r2, 1.0 - 1e-12);
}

TEST(Inflection, NoisyStepWithinReportedUncertaintyAndCalibrated) {
  // 200 noisy realisations of a known step: the true inflection lies within one reported
  // standard error in about 68 % of them (binomial 3-sigma band for 200 trials: 0.58 .. 0.78).
  const Step s;
  const std::vector<double> x = vem_grid(1.4);
  const int trials = 200;
  int within_x = 0, within_slope = 0, within_y = 0;
  for (int t = 0; t < trials; ++t) {
    Random rng(1000 + t);
    std::vector<double> y;
    for (double q : x) y.push_back(s(q) + 0.08 * rng.normal());
    const Inflection inf = find_inflection(x, y);
    ASSERT_TRUE(inf.found) << inf.message;
    ASSERT_GT(inf.x_err, 0.0);
    if (std::abs(inf.x - s.x0) < inf.x_err) ++within_x;
    if (std::abs(inf.slope - s.slope()) < inf.slope_err) ++within_slope;
    if (std::abs(inf.y - s.y0()) < inf.y_err) ++within_y;
    if (t == 0) {
      // One realisation: within three standard errors (statistical and window together).
      EXPECT_LT(std::abs(inf.x - s.x0), 3.0 * std::hypot(inf.x_err, inf.x_window));
      EXPECT_LT(std::abs(inf.slope - s.slope()), 3.0 * std::hypot(inf.slope_err, inf.slope_window));
    }
  }
  for (int within : {within_x, within_slope, within_y}) {
    const double fraction = static_cast<double>(within) / trials;
    EXPECT_GT(fraction, 0.58);
    EXPECT_LT(fraction, 0.78);
  }
}

TEST(Inflection, SymmetricNonLogisticStepFindsItsCentre) {
  // An error-function step with a power-law tail after it (like stage III): the inflection of
  // the step is at its centre; the windowed fit must not be pulled away by the tail.
  const double x0 = 0.9, sigma = 0.03;
  const std::vector<double> x = vem_grid(1.3);
  Random rng(7);
  std::vector<double> y;
  for (double q : x) {
    double v = 1.0 + 2.5 * 0.5 * (1.0 + std::erf((q - x0) / (sigma * std::numbers::sqrt2)));
    if (q > x0 + 4 * sigma) v += 1.5 * std::pow(q - x0 - 4 * sigma, 0.4);
    y.push_back(v + 0.03 * rng.normal());
  }
  const Inflection inf = find_inflection(x, y);
  ASSERT_TRUE(inf.found) << inf.message;
  EXPECT_LT(std::abs(inf.x - x0), 3.0 * std::hypot(inf.x_err, inf.x_window));
  EXPECT_LT(inf.x_hi, 1.3);  // the window excluded the end of the tail
}

TEST(Inflection, RefusesCurvesWithoutAStep) {
  const std::vector<double> x = vem_grid(1.0);
  std::vector<double> flat(x.size(), 2.0);
  EXPECT_FALSE(find_inflection(x, flat).found);
  std::vector<double> falling;
  for (double q : x) falling.push_back(5.0 - q);
  EXPECT_FALSE(find_inflection(x, falling).found);
  EXPECT_FALSE(find_inflection({0.1, 0.2, 0.3}, {1.0, 2.0, 3.0}).found);
  EXPECT_THROW(find_inflection({0.1, 0.2}, {1.0}), InputError);
  EXPECT_THROW(find_inflection({0.1, NAN}, {1.0, 2.0}), InputError);
}

TEST(PowerLaw, ExactPowerLawIsRecovered) {
  const double xi = 0.62, yi = 3.1, amplitude = 6.0, beta = 0.37;
  std::vector<double> x, y;
  for (double phi = 0.55; phi < 0.70; phi += 0.0025) {
    x.push_back(phi);
    y.push_back(phi > xi ? yi + amplitude * std::pow(phi - xi, beta) : yi - 1.0);
  }
  const PowerLaw fit = fit_power_law(x, y, xi, yi);
  ASSERT_TRUE(fit.found) << fit.message;
  EXPECT_NEAR(fit.beta, beta, 1e-9);
  EXPECT_NEAR(fit.amplitude, amplitude, 1e-8);
  EXPECT_GT(fit.r2, 1.0 - 1e-12);
  int above = 0;
  for (double phi : x) above += phi > xi ? 1 : 0;
  EXPECT_EQ(fit.points, above);  // only the points above the inflection
}

TEST(PowerLaw, NoisyBetaWithinReportedUncertaintyAndCalibrated) {
  const double xi = 0.62, yi = 3.1, amplitude = 6.0, beta = 0.37;
  const int trials = 200;
  int within = 0;
  for (int t = 0; t < trials; ++t) {
    Random rng(500 + t);
    std::vector<double> x, y;
    for (double phi = 0.6225; phi < 0.72; phi += 0.0025) {
      x.push_back(phi);
      y.push_back(yi + amplitude * std::pow(phi - xi, beta) + 0.02 * rng.normal());
    }
    const PowerLaw fit = fit_power_law(x, y, xi, yi);
    ASSERT_TRUE(fit.found) << fit.message;
    if (std::abs(fit.beta - beta) < fit.beta_err) ++within;
    if (t == 0) {
      EXPECT_LT(std::abs(fit.beta - beta), 3.0 * fit.beta_err);
    }
  }
  const double fraction = static_cast<double>(within) / trials;
  EXPECT_GT(fraction, 0.58);
  EXPECT_LT(fraction, 0.78);
}

TEST(PowerLaw, TooFewPointsAndBadInput) {
  EXPECT_FALSE(fit_power_law({0.6, 0.61, 0.63}, {1.0, 2.0, 3.0}, 0.62, 2.0).found);
  EXPECT_THROW(fit_power_law({0.6}, {1.0, 2.0}, 0.5, 0.5), InputError);
  EXPECT_THROW(fit_power_law({0.6}, {1.0}, 0.5, 0.5, PowerLawOptions{0.2, 0.1, 4}), InputError);
}
