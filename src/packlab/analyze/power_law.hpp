// The scaling of the coordination number above the inflection point
// (vem-void-expansion-method eq. 9): CN - CN_i = A (Phi_T - Phi_T,i)^beta.
//
// Method: the points with Phi_T - Phi_T,i in (min_excess, max_excess] and CN > CN_i; start
// values from the straight line through log(CN - CN_i) against log(Phi_T - Phi_T,i), then a
// Levenberg-Marquardt least-squares fit of A and beta on the linear scale (as the paper's
// R^2 > 0.999 are of the curves themselves). R^2 = 1 - SS_res / SS_tot of CN - CN_i on that
// linear scale; beta_err is one standard error from the fit's covariance.
#pragma once

#include <string>
#include <vector>

namespace packlab::analyze {

struct PowerLawOptions {
  double min_excess = 0.0;  // smallest Phi_T - Phi_T,i used (exclusive)
  double max_excess = 1.0;  // largest Phi_T - Phi_T,i used (inclusive)
  int min_points = 4;
};

struct PowerLaw {
  bool found = false;
  std::string message;
  double beta = 0.0, beta_err = 0.0;
  double amplitude = 0.0, amplitude_err = 0.0;  // A
  double r2 = 0.0;
  int points = 0;
  double model(double excess) const;  // A excess^beta
};

// x = Phi_T, y = CN per point; x_i, y_i = Phi_T,i, CN_i from the inflection point.
PowerLaw fit_power_law(const std::vector<double>& x, const std::vector<double>& y, double x_i, double y_i,
                       const PowerLawOptions& options = {});

}  // namespace packlab::analyze
