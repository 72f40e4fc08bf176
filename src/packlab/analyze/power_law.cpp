// GCC 12 reports false 'may be used uninitialized' warnings inside Eigen's AVX-512 kernels
// (avx512fintrin.h, -march=native) when they are inlined here.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include "packlab/analyze/power_law.hpp"

#include <cmath>

#include "packlab/analyze/inflection.hpp"
#include "packlab/core/error.hpp"

namespace packlab::analyze {

double PowerLaw::model(double excess) const { return amplitude * std::pow(excess, beta); }

PowerLaw fit_power_law(const std::vector<double>& x, const std::vector<double>& y, double x_i, double y_i,
                       const PowerLawOptions& o) {
  if (x.size() != y.size()) fail_input("fit_power_law: x and y differ in length");
  require(o.min_excess >= 0.0, "min_excess", o.min_excess, ">= 0");
  require(o.max_excess > o.min_excess, "max_excess", o.max_excess, "> min_excess");
  require(o.min_points >= 3, "min_points", o.min_points, ">= 3");
  PowerLaw out;
  std::vector<double> dx, dy;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double ex = x[k] - x_i, ey = y[k] - y_i;
    if (!std::isfinite(ex) || !std::isfinite(ey)) fail_input("fit_power_law: non-finite data");
    if (ex > o.min_excess && ex <= o.max_excess && ey > 0.0) {
      dx.push_back(ex);
      dy.push_back(ey);
    }
  }
  const int n = static_cast<int>(dx.size());
  out.points = n;
  if (n < o.min_points) {
    out.message = "too few points above the inflection";
    return out;
  }
  // Straight line in log-log for the start values.
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int k = 0; k < n; ++k) {
    const double lx = std::log(dx[k]), ly = std::log(dy[k]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  const double denom = n * sxx - sx * sx;
  if (!(std::abs(denom) > 0.0)) {
    out.message = "all points at the same Phi_T";
    return out;
  }
  const double beta0 = (n * sxy - sx * sy) / denom;
  const double log_a0 = (sy - beta0 * sx) / n;
  Eigen::VectorXd start(2);
  start << log_a0, beta0;
  const auto evaluate = [&](const Eigen::VectorXd& p, Eigen::VectorXd& r, Eigen::MatrixXd& J) {
    const double a = std::exp(p[0]), beta = p[1];
    for (int k = 0; k < n; ++k) {
      const double m = a * std::pow(dx[k], beta);
      r[k] = m - dy[k];
      J(k, 0) = m;
      J(k, 1) = m * std::log(dx[k]);
    }
  };
  const auto ls = detail::levenberg_marquardt(evaluate, start, n);
  if (!ls.converged || !ls.params.allFinite()) {
    out.message = "the power-law fit did not converge";
    return out;
  }
  out.found = true;
  out.message = "ok";
  out.amplitude = std::exp(ls.params[0]);
  out.beta = ls.params[1];
  out.beta_err = std::sqrt(std::max(0.0, ls.covariance(1, 1)));
  out.amplitude_err = out.amplitude * std::sqrt(std::max(0.0, ls.covariance(0, 0)));
  double mean = 0.0;
  for (double v : dy) mean += v;
  mean /= n;
  double sst = 0.0;
  for (double v : dy) sst += (v - mean) * (v - mean);
  out.r2 = sst > 0.0 ? 1.0 - ls.residual_sum / sst : 0.0;
  return out;
}

}  // namespace packlab::analyze
