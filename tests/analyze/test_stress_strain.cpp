// Evaluation of mechanical tests (analyze/stress_strain): the max-tangent Young's modulus of
// synthetic stress-strain curves, per-type statistics of particle stresses, curve columns.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "packlab/analyze/stress_strain.hpp"
#include "packlab/core/packing.hpp"
#include "packlab/io/table.hpp"
#include "packlab/mechanics/uniaxial_compression.hpp"

using namespace packlab;
using namespace packlab::analyze;

TEST(StressStrain, ModulusFitRecoversTheSlopeOfTheLinearPart) {
  // Toe (quadratic contact formation up to strain 0.004), linear with slope 1.7 GPa, softening
  // past strain 0.02, a peak and a drop: the max-tangent fit returns the linear slope.
  const double slope = 1.7e9, toe = 0.004;
  std::vector<double> strain, stress;
  for (int k = 0; k <= 400; ++k) {
    const double e = 0.03 * k / 400.0;
    double s;
    if (e < toe)
      s = 0.5 * slope * e * e / toe;
    else if (e < 0.02)
      s = 0.5 * slope * toe + slope * (e - toe);
    else
      s = 0.5 * slope * toe + slope * (0.02 - toe) + slope * (e - 0.02) - 0.5 * slope * (e - 0.02) * (e - 0.02) / 0.004;
    if (e > 0.026) s *= std::exp(-(e - 0.026) / 0.001);
    strain.push_back(e);
    stress.push_back(s);
  }
  const ModulusFit fit = fit_youngs_modulus(strain, stress);
  ASSERT_TRUE(fit.found);
  EXPECT_NEAR(fit.youngs_modulus, slope, 1e-3 * slope);
  EXPECT_GE(fit.strain_begin, toe - 1e-12);
  EXPECT_LE(fit.strain_end, 0.02 + 1e-12);
  EXPECT_GT(fit.r2, 0.9999);
}

TEST(StressStrain, StressByTypeAveragesFreeParticlesPerType) {
  Packing p;
  p.box.length = {1, 1, 1};
  for (int k = 0; k < 4; ++k) p.add({0.1 + 0.2 * k, 0.5, 0.5}, 0.05, k < 3 ? particle_type::structural : particle_type::coating);
  p.fixed = {1, 0, 0, 0};
  std::vector<std::array<double, 9>> s(4, std::array<double, 9>{});
  const double xx[] = {100, 1, 3, 7}, zz[] = {100, -4, -8, -2};
  for (int k = 0; k < 4; ++k) {
    s[static_cast<std::size_t>(k)][0] = xx[k];
    s[static_cast<std::size_t>(k)][8] = zz[k];
  }
  const auto t = stress_by_type(p, s);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].type, particle_type::structural);
  EXPECT_EQ(t[0].particles, 2u);  // the fixed one is left out
  EXPECT_DOUBLE_EQ(t[0].mean[0], 2.0);
  EXPECT_DOUBLE_EQ(t[0].mean[2], -6.0);
  EXPECT_NEAR(t[0].sd[2], std::sqrt(8.0), 1e-12);
  EXPECT_EQ(t[1].type, particle_type::coating);
  EXPECT_DOUBLE_EQ(t[1].mean[0], 7.0);
}

TEST(StressStrain, CurveColumnsWriteTheCsvOfTheCurve) {
  mechanics::UniaxialCompressionPoint p;
  p.step = 12;
  p.time = 0.5;
  p.strain = 1.0 / 3.0;
  p.broken_bonds = 4;
  const std::string csv = io::to_csv(mechanics::curve_columns({p}));
  EXPECT_EQ(csv,
            "step,time,displacement,strain,force,stress,kinetic_energy,strain_energy,broken_bonds\n"
            "12,0.5,0,0.33333333333333331,0,0,0,0,4\n");
}
