// Porosity laws (bpm-inverse-opals eq. 22-26): fits recover known exponents from synthetic data.
#include <gtest/gtest.h>

#include <cmath>

#include "packlab/analyze/porosity_laws.hpp"
#include "packlab/core/error.hpp"

using namespace packlab;
using namespace packlab::analyze;

namespace {
// Six porosities as in §4, five "realizations" each with a deterministic +-2 % scatter.
void synthetic(PorosityLaw law, double e0, double exponent, std::vector<double>& eps, std::vector<double>& y) {
  const double scatter[] = {-0.02, -0.01, 0.0, 0.01, 0.02};
  PorosityFit truth;
  truth.law = law;
  truth.e0 = e0;
  truth.exponent = exponent;
  for (double e : {0.39, 0.45, 0.49, 0.55, 0.59, 0.63})
    for (double s : scatter) {
      eps.push_back(e);
      y.push_back(truth.model(e) * (1.0 + s));
    }
}
}  // namespace

TEST(PorosityLaws, PowerLawRecoversM) {
  std::vector<double> eps, y;
  synthetic(PorosityLaw::power, 22.06e9, 1.92, eps, y);
  const PorosityFit fixed = fit_porosity_law(PorosityLaw::power, eps, y, 22.06e9);
  EXPECT_NEAR(fixed.exponent, 1.92, 0.01);
  EXPECT_EQ(fixed.e0, 22.06e9);
  const PorosityFit free = fit_porosity_law(PorosityLaw::power, eps, y);
  EXPECT_NEAR(free.exponent, 1.92, 0.05);
  EXPECT_NEAR(free.e0, 22.06e9, 0.05 * 22.06e9);
  // Standard errors are finite and of the size of the scatter (Pa-sized E0 is scaled out).
  EXPECT_GT(free.e0_err, 0.0);
  EXPECT_LT(free.e0_err, 0.05 * free.e0);
  EXPECT_GT(free.exponent_err, 0.0);
  EXPECT_LT(free.exponent_err, 0.2);
  // The exponential law describes power-law data worse.
  const PorosityFit expo = fit_porosity_law(PorosityLaw::exponential, eps, y, 22.06e9);
  EXPECT_GT(expo.rss, 2 * fixed.rss);
}

TEST(PorosityLaws, ExponentialLawRecoversB) {
  std::vector<double> eps, y;
  synthetic(PorosityLaw::exponential, 576.3e6, 3.85, eps, y);  // eq. 26, strength
  const PorosityFit f = fit_porosity_law(PorosityLaw::exponential, eps, y);
  EXPECT_NEAR(f.exponent, 3.85, 0.1);
  EXPECT_NEAR(f.e0, 576.3e6, 0.05 * 576.3e6);
  EXPECT_LT(f.rms_relative, 0.02);
  const PorosityFit fixed = fit_porosity_law(PorosityLaw::exponential, eps, y, 576.3e6);
  EXPECT_NEAR(fixed.exponent, 3.85, 0.02);
}

TEST(PorosityLaws, BadInputIsAnInputError) {
  EXPECT_THROW(fit_porosity_law(PorosityLaw::power, {0.1, 0.2}, {1.0, 0.9}), InputError);  // 2 points, E0 free
  EXPECT_THROW(fit_porosity_law(PorosityLaw::power, {0.1, 1.2, 0.3}, {1.0, 0.9, 0.8}), InputError);
  EXPECT_THROW(fit_porosity_law(PorosityLaw::power, {0.1, 0.2, 0.3}, {1.0, -0.9, 0.8}), InputError);
  EXPECT_THROW(porosity_law_from_name("linear"), InputError);
}
