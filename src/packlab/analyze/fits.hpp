// Nonlinear least-squares fits (Eigen's Levenberg-Marquardt, MINPACK's lmder) with standard
// errors from the parameter covariance and the coefficient of determination R^2 = 1 - RSS/TSS.
// Two covariances:
//  - independent errors of equal variance (the textbook case): s^2 (J^T J)^-1, s^2 = RSS/(n-p);
//  - data with a known covariance Sigma (e.g. an empirical distribution function, whose
//    values at different x are strongly correlated): the sandwich
//    (J^T J)^-1 J^T Sigma J (J^T J)^-1 of the unweighted estimator. The degree-of-heterogeneity fit of the pore-size
// distribution (doh-elastic-properties eq. 6) is one instance.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace packlab::analyze {

// y(x; p) and, when `gradient` is not null, dy/dp (gradient->size() == p.size()).
using FitModel = std::function<double(double x, const std::vector<double>& p, std::vector<double>* gradient)>;

struct FitResult {
  std::vector<double> params;
  std::vector<double> std_errors;               // sqrt of the covariance diagonal
  std::vector<std::vector<double>> covariance;  // sandwich with the data covariance, else s^2 (J^T J)^-1
  std::vector<double> ls_std_errors;            // from s^2 (J^T J)^-1 in either case
  double rss = 0.0;                             // residual sum of squares
  double r2 = 0.0;                              // 1 - RSS / TSS
  long points = 0;                              // n
  long iterations = 0;                          // Jacobian evaluations
  bool converged = false;                       // MINPACK reported a tolerance criterion
  std::string status;                           // MINPACK's reason for stopping
};

// Unweighted least squares of y against model(x; p) from the start p0. InputError when the
// data are unusable (sizes differ, fewer points than parameters + 1, non-finite values).
// `data_covariance` (n x n, optional) selects the sandwich covariance.
FitResult fit_least_squares(const FitModel& model, const std::vector<double>& x, const std::vector<double>& y,
                            const std::vector<double>& p0,
                            const std::vector<std::vector<double>>* data_covariance = nullptr);

// doh-elastic-properties eq. 6: P(r_P > r) = 1 - erf((x - b) / (a sqrt 2)), x = r / r0.
double pore_erf_model(double x, double a, double b);

struct ErfFit {
  double a = 0.0, b = 0.0;                // width (degree of heterogeneity) and location, in units of r0
  double a_err = 0.0, b_err = 0.0;        // standard errors (sandwich when a data covariance was given)
  double a_ls_err = 0.0, b_ls_err = 0.0;  // textbook s^2 (J^T J)^-1 standard errors
  double r2 = 0.0;
  long points = 0;
  bool converged = false;
};

// Fits eq. 6 to (x, P) pairs. The start values come from the data (the x where P crosses
// 1/2 and 1/10, which eq. 6 puts at b + 0.674 a and b + 1.645 a), so callers need not guess.
ErfFit fit_pore_erf(const std::vector<double>& x, const std::vector<double>& probability,
                    const std::vector<std::vector<double>>* data_covariance = nullptr);

}  // namespace packlab::analyze
