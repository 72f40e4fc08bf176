// GCC 12 reports false 'may be used uninitialized' warnings inside Eigen's AVX-512 kernels
// (avx512fintrin.h, -march=native) when they are inlined here.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include "packlab/analyze/inflection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "packlab/core/error.hpp"

namespace packlab::analyze {

double total_volume_fraction(double phi_s, double q, double number_ratio) {
  return phi_s * (1.0 + q * q * q * number_ratio);
}

InflectionVolumeFraction inflection_volume_fraction(double phi_s, double number_ratio, const Inflection& inflection) {
  InflectionVolumeFraction out;
  out.value = total_volume_fraction(phi_s, inflection.x, number_ratio);
  out.err = 3.0 * phi_s * number_ratio * inflection.x * inflection.x * inflection.x_err;
  return out;
}

namespace detail {

LeastSquaresResult levenberg_marquardt(
    const std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&, Eigen::MatrixXd&)>& evaluate,
    Eigen::VectorXd start, int residuals, int max_iterations) {
  const Eigen::Index p = start.size();
  LeastSquaresResult out;
  Eigen::VectorXd r(residuals), r_try(residuals);
  Eigen::MatrixXd J(residuals, p), J_try(residuals, p);
  Eigen::VectorXd x = std::move(start);
  evaluate(x, r, J);
  double cost = r.squaredNorm();
  double lambda = 1e-3;
  for (int it = 0; it < max_iterations && std::isfinite(cost); ++it) {
    const Eigen::MatrixXd A = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * r;
    bool improved = false;
    for (int tries = 0; tries < 30; ++tries) {
      Eigen::MatrixXd M = A;
      for (Eigen::Index k = 0; k < p; ++k) M(k, k) += lambda * std::max(A(k, k), 1e-300);
      const Eigen::VectorXd step = M.ldlt().solve(-g);
      if (!step.allFinite()) {
        lambda *= 10.0;
        continue;
      }
      const Eigen::VectorXd x_try = x + step;
      evaluate(x_try, r_try, J_try);
      const double cost_try = r_try.squaredNorm();
      if (std::isfinite(cost_try) && cost_try <= cost) {
        const double relative = (cost - cost_try) / std::max(cost, 1e-300);
        const double step_size = step.norm() / (x.norm() + 1e-12);
        x = x_try;
        r = r_try;
        J = J_try;
        cost = cost_try;
        lambda = std::max(lambda / 10.0, 1e-12);
        improved = true;
        if (relative < 1e-14 || step_size < 1e-12) out.converged = true;
        break;
      }
      lambda *= 10.0;
    }
    if (!improved) {
      out.converged = true;  // no downhill step left: a (local) minimum
      break;
    }
    if (out.converged) break;
  }
  out.params = x;
  out.residual_sum = cost;
  const Eigen::MatrixXd A = J.transpose() * J;
  const double dof = static_cast<double>(std::max<Eigen::Index>(1, residuals - p));
  Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  if (lu.isInvertible())
    out.covariance = lu.inverse() * (cost / dof);
  else
    out.covariance = Eigen::MatrixXd::Constant(p, p, std::numeric_limits<double>::infinity());
  out.converged = out.converged && x.allFinite();
  return out;
}

}  // namespace detail

double Inflection::model(double xv) const {
  return a + b * (xv - x) + c / (1.0 + std::exp(-(xv - x) / width));
}

namespace {

struct Fit {
  bool ok = false;
  Eigen::VectorXd p;  // a, b, c, x0, ln w
  Eigen::MatrixXd cov;
  double ssr = 0.0;
  int points = 0;
  double lo = 0.0, hi = 0.0;
  double r2 = 0.0;
};

double logistic(double u) { return 1.0 / (1.0 + std::exp(-u)); }

Fit fit_window(const std::vector<double>& x, const std::vector<double>& y, double lo, double hi,
               const Eigen::VectorXd& start) {
  std::vector<int> idx;
  for (int k = 0; k < static_cast<int>(x.size()); ++k)
    if (x[k] >= lo && x[k] <= hi) idx.push_back(k);
  Fit f;
  f.lo = lo;
  f.hi = hi;
  f.points = static_cast<int>(idx.size());
  if (f.points < 6) return f;
  const auto evaluate = [&](const Eigen::VectorXd& p, Eigen::VectorXd& r, Eigen::MatrixXd& J) {
    const double a = p[0], b = p[1], c = p[2], x0 = p[3], w = std::exp(p[4]);
    for (int m = 0; m < f.points; ++m) {
      const double xv = x[idx[m]];
      const double u = (xv - x0) / w;
      const double s = logistic(u);
      const double ds = s * (1.0 - s);
      r[m] = a + b * (xv - x0) + c * s - y[idx[m]];
      J(m, 0) = 1.0;
      J(m, 1) = xv - x0;
      J(m, 2) = s;
      J(m, 3) = -b - c * ds / w;
      J(m, 4) = -c * ds * u;
    }
  };
  const auto ls = detail::levenberg_marquardt(evaluate, start, f.points);
  f.ok = ls.converged && ls.params.allFinite() && ls.covariance.allFinite();
  f.p = ls.params;
  f.cov = ls.covariance;
  f.ssr = ls.residual_sum;
  double mean = 0.0;
  for (int k : idx) mean += y[k];
  mean /= f.points;
  double sst = 0.0;
  for (int k : idx) sst += (y[k] - mean) * (y[k] - mean);
  f.r2 = sst > 0.0 ? 1.0 - f.ssr / sst : 0.0;
  return f;
}

// Window of half-width `widths` w around the fit's x0, widened to hold at least min_points.
std::pair<double, double> window_of(const std::vector<double>& xs, const Eigen::VectorXd& p, double widths,
                                    int min_points) {
  const double x0 = p[3], w = std::exp(p[4]);
  double half = widths * w;
  std::vector<double> distance(xs.size());
  for (std::size_t k = 0; k < xs.size(); ++k) distance[k] = std::abs(xs[k] - x0);
  std::sort(distance.begin(), distance.end());
  const std::size_t need = std::min(distance.size(), static_cast<std::size_t>(min_points));
  if (need > 0) half = std::max(half, distance[need - 1]);
  return {x0 - half, x0 + half};
}

// Iterates fit -> window -> fit until the window (its point set) no longer changes.
Fit fit_iterated(const std::vector<double>& x, const std::vector<double>& y, const Fit& first, double widths,
                 const InflectionOptions& o) {
  Fit f = first;
  for (int it = 0; it < o.max_iterations && f.ok; ++it) {
    const auto [lo, hi] = window_of(x, f.p, widths, o.min_points);
    Fit next = fit_window(x, y, lo, hi, f.p);
    if (!next.ok) break;  // keep the last good fit
    const bool same = next.points == f.points && lo >= f.lo - 1e-300 && hi <= f.hi + 1e-300 &&
                      std::abs(next.p[3] - f.p[3]) <= 1e-9 * (std::abs(f.p[3]) + std::exp(f.p[4]));
    f = next;
    if (same) break;
  }
  return f;
}

}  // namespace

Inflection find_inflection(const std::vector<double>& x_in, const std::vector<double>& y_in,
                           const InflectionOptions& o) {
  if (x_in.size() != y_in.size()) fail_input("find_inflection: x and y differ in length");
  require(o.window_widths > 0.0, "window_widths", o.window_widths, "> 0");
  require(o.min_points >= 6, "min_points", o.min_points, ">= 6");
  Inflection out;
  const std::size_t n = x_in.size();
  for (std::size_t k = 0; k < n; ++k)
    if (!std::isfinite(x_in[k]) || !std::isfinite(y_in[k])) fail_input("find_inflection: non-finite data");
  if (n < 8) {  // five parameters and a few degrees of freedom
    out.message = "too few points";
    return out;
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return x_in[i] < x_in[j]; });
  std::vector<double> x(n), y(n);
  for (std::size_t k = 0; k < n; ++k) {
    x[k] = x_in[order[k]];
    y[k] = y_in[order[k]];
  }
  if (!(x.back() > x.front())) {
    out.message = "all x are equal";
    return out;
  }

  // Start values from a moving average: the steepest point and the rise.
  const int h = std::max(1, (o.smoothing_points > 0 ? o.smoothing_points : std::max(3, static_cast<int>(n) / 20)) / 2);
  std::vector<double> smooth(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t lo = k >= static_cast<std::size_t>(h) ? k - h : 0, hi = std::min(n - 1, k + h);
    double s = 0.0;
    for (std::size_t m = lo; m <= hi; ++m) s += y[m];
    smooth[k] = s / static_cast<double>(hi - lo + 1);
  }
  double best_slope = -std::numeric_limits<double>::infinity();
  std::size_t best = n / 2;
  const std::size_t step = static_cast<std::size_t>(h);
  for (std::size_t k = step; k + step < n; ++k) {
    const double dx = x[k + step] - x[k - step];
    if (dx <= 0.0) continue;
    const double slope = (smooth[k + step] - smooth[k - step]) / dx;
    if (slope > best_slope) {
      best_slope = slope;
      best = k;
    }
  }
  const auto [mn, mx] = std::minmax_element(smooth.begin(), smooth.end());
  const double rise = *mx - *mn;
  if (!(rise > 0.0) || !(best_slope > 0.0)) {
    out.message = "the curve does not rise";
    return out;
  }
  Eigen::VectorXd start(5);
  const double w0 = std::clamp(rise / (4.0 * best_slope), 1e-3 * (x.back() - x.front()), x.back() - x.front());
  start << *mn, 0.0, rise, x[best], std::log(w0);

  // First fit in the window around the steepest point of the smoothed curve, else on all points.
  const auto [lo0, hi0] = window_of(x, start, o.window_widths, o.min_points);
  Fit first = fit_window(x, y, lo0, hi0, start);
  if (!first.ok) first = fit_window(x, y, x.front(), x.back(), start);
  if (!first.ok) {
    out.message = "the logistic fit did not converge";
    return out;
  }
  const Fit f = fit_iterated(x, y, first, o.window_widths, o);
  if (!f.ok || !(f.p[2] > 0.0)) {
    out.message = f.ok ? "the fitted step does not rise" : "the logistic fit did not converge";
    return out;
  }
  out.found = true;
  out.message = "ok";
  out.a = f.p[0];
  out.b = f.p[1];
  out.c = f.p[2];
  out.x = f.p[3];
  out.width = std::exp(f.p[4]);
  out.y = out.a + 0.5 * out.c;
  out.slope = out.b + out.c / (4.0 * out.width);
  out.x_lo = f.lo;
  out.x_hi = f.hi;
  out.points = f.points;
  out.r2 = f.r2;
  out.residual_sd = std::sqrt(f.ssr / std::max(1, f.points - 5));
  const auto err = [&](const Eigen::VectorXd& grad) { return std::sqrt(std::max(0.0, grad.dot(f.cov * grad))); };
  Eigen::VectorXd gx = Eigen::VectorXd::Zero(5), gy = Eigen::VectorXd::Zero(5), gs = Eigen::VectorXd::Zero(5);
  gx[3] = 1.0;
  gy[0] = 1.0;
  gy[2] = 0.5;
  gs[1] = 1.0;
  gs[2] = 1.0 / (4.0 * out.width);
  gs[4] = -out.c / (4.0 * out.width);
  out.x_err = err(gx);
  out.y_err = err(gy);
  out.slope_err = err(gs);
  if (o.window_sensitivity) {
    for (double factor : {0.75, 1.25}) {
      const Fit g = fit_iterated(x, y, f, o.window_widths * factor, o);
      if (!g.ok || !(g.p[2] > 0.0)) continue;
      const double gw = std::exp(g.p[4]);
      out.x_window = std::max(out.x_window, std::abs(g.p[3] - out.x));
      out.y_window = std::max(out.y_window, std::abs(g.p[0] + 0.5 * g.p[2] - out.y));
      out.slope_window = std::max(out.slope_window, std::abs(g.p[1] + g.p[2] / (4.0 * gw) - out.slope));
    }
  }
  return out;
}

}  // namespace packlab::analyze
