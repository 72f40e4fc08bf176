// The inflection point of a step-shaped curve y(x), for the CN(q) curves of the void expansion
// method (vem-void-expansion-method §3: q_i, CN_i and the maximum slope dCN/dq|_i; eq. 5:
// Phi_T,i = Phi_S (1 + q_i^3 n)).
//
// Method (docs/vem.md): a logistic step on a linear baseline,
//   y(x) = a + b (x - x0) + c / (1 + exp(-(x - x0) / w)),
// fitted by Levenberg-Marquardt least squares. Its second derivative vanishes at x0, where the
// slope b + c / (4 w) is the largest (c > 0), so x_i = x0, y_i = a + c/2, slope = b + c/(4w).
// The CN(q) curve is a sigmoid only near the transition (stage III grows like a power law), so
// the fit is repeated on the window |x - x0| <= window_widths * w around the current estimate
// until the window stops changing. Start values come from the largest slope of a moving-average
// smoothed curve.
//
// Uncertainties: `*_err` are one standard error from the covariance s^2 (J^T J)^-1 of the fit
// in its final window (s^2 = residual sum of squares / (points - 5)), propagated to CN_i and
// the slope linearly. `*_window` are the largest changes when the window is 0.75x and 1.25x as
// wide (the model error on a curve that is not exactly a logistic); quote
// sqrt(err^2 + window^2) as the total.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace packlab::analyze {

// Eq. 5: total (structural + void) volume fraction Phi_S (1 + q^3 n), n = N_V / N_S.
double total_volume_fraction(double phi_s, double q, double number_ratio);

struct InflectionOptions {
  double window_widths = 4.0;  // fit window half-width in units of the logistic width w
  int min_points = 30;         // the window never holds fewer points than this (a narrower one
                               // lets the baseline slope and the step trade off and run away)
  int max_iterations = 20;     // window refinements
  int smoothing_points = 0;    // moving-average width for the start values; 0 = max(3, points / 20)
  bool window_sensitivity = true;  // also fit with 0.75x and 1.25x the window (the *_window fields)
};

struct Inflection {
  bool found = false;     // false: too few points, no rise, or the fit failed (see `message`)
  std::string message;
  double x = 0.0, x_err = 0.0, x_window = 0.0;              // q_i
  double y = 0.0, y_err = 0.0, y_window = 0.0;              // CN_i
  double slope = 0.0, slope_err = 0.0, slope_window = 0.0;  // dCN/dq at q_i
  double a = 0.0, b = 0.0, c = 0.0, width = 0.0;            // fitted model (width = w)
  double x_lo = 0.0, x_hi = 0.0;                            // the final fit window
  int points = 0;                                           // points in that window
  double r2 = 0.0;                                          // coefficient of determination there
  double residual_sd = 0.0;                                 // s

  double model(double x_value) const;  // the fitted curve
};

// x need not be sorted; x and y of equal size, finite.
Inflection find_inflection(const std::vector<double>& x, const std::vector<double>& y,
                           const InflectionOptions& options = {});

// Phi_T,i and its standard error from q_i +- q_err (eq. 5).
struct InflectionVolumeFraction {
  double value = 0.0, err = 0.0;
};
InflectionVolumeFraction inflection_volume_fraction(double phi_s, double number_ratio, const Inflection& inflection);

namespace detail {

// Levenberg-Marquardt least squares: minimises |r(p)|^2 with the residuals r and their
// Jacobian dr/dp supplied by `evaluate(p, r, J)`. Returns false when it did not converge.
struct LeastSquaresResult {
  Eigen::VectorXd params;
  Eigen::MatrixXd covariance;  // s^2 (J^T J)^-1 at the solution
  double residual_sum = 0.0;   // |r|^2
  bool converged = false;
};
LeastSquaresResult levenberg_marquardt(
    const std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&, Eigen::MatrixXd&)>& evaluate,
    Eigen::VectorXd start, int residuals, int max_iterations = 200);

}  // namespace detail

}  // namespace packlab::analyze
