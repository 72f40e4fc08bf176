#include "packlab/analyze/fits.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numbers>

// GCC 12 reports a false -Wmaybe-uninitialized inside Eigen's AVX-512 packet transpose
// (GeneralBlockPanelKernel, used by the Levenberg-Marquardt solver) under -march=native.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <Eigen/Dense>
#include <unsupported/Eigen/NonLinearOptimization>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

#include "packlab/core/error.hpp"

namespace packlab::analyze {

namespace {

// The functor interface of Eigen's LevenbergMarquardt: residuals f_i = model(x_i) - y_i.
struct Residuals {
  const FitModel& model;
  const std::vector<double>& x;
  const std::vector<double>& y;
  int parameter_count;

  int inputs() const { return parameter_count; }
  int values() const { return static_cast<int>(x.size()); }

  int operator()(const Eigen::VectorXd& p, Eigen::VectorXd& f) const {
    const std::vector<double> pv(p.data(), p.data() + p.size());
    for (int i = 0; i < values(); ++i) f[i] = model(x[i], pv, nullptr) - y[i];
    return 0;
  }
  int df(const Eigen::VectorXd& p, Eigen::MatrixXd& jac) const {
    const std::vector<double> pv(p.data(), p.data() + p.size());
    std::vector<double> g(pv.size());
    for (int i = 0; i < values(); ++i) {
      (void)model(x[i], pv, &g);
      for (int k = 0; k < parameter_count; ++k) jac(i, k) = g[k];
    }
    return 0;
  }
};

std::string status_name(Eigen::LevenbergMarquardtSpace::Status s) {
  using namespace Eigen::LevenbergMarquardtSpace;
  switch (s) {
    case RelativeReductionTooSmall:
      return "relative reduction of the sum of squares below ftol";
    case RelativeErrorTooSmall:
      return "relative change of the parameters below xtol";
    case RelativeErrorAndReductionTooSmall:
      return "sum of squares and parameters converged";
    case CosinusTooSmall:
      return "residuals orthogonal to the Jacobian";
    case TooManyFunctionEvaluation:
      return "too many function evaluations";
    case FtolTooSmall:
      return "ftol too small";
    case XtolTooSmall:
      return "xtol too small";
    case GtolTooSmall:
      return "gtol too small";
    case ImproperInputParameters:
      return "improper input parameters";
    default:
      return "stopped";
  }
}

}  // namespace

FitResult fit_least_squares(const FitModel& model, const std::vector<double>& x, const std::vector<double>& y,
                            const std::vector<double>& p0, const std::vector<std::vector<double>>* data_covariance) {
  const auto n = static_cast<long>(x.size());
  const auto p = static_cast<long>(p0.size());
  if (y.size() != x.size())
    fail_input(fmt::format("fit: {} x values but {} y values: must be equal", x.size(), y.size()));
  require(p >= 1, "fit parameters", static_cast<double>(p), "at least 1");
  require(n > p, "fit points", static_cast<double>(n), fmt::format("more than the {} parameters", p));
  for (long i = 0; i < n; ++i)
    if (!std::isfinite(x[i]) || !std::isfinite(y[i]))
      fail_input(fmt::format("fit: data point {} = ({}, {}): must be finite", i, x[i], y[i]));

  Residuals functor{model, x, y, static_cast<int>(p)};
  Eigen::LevenbergMarquardt<Residuals> lm(functor);
  lm.parameters.maxfev = 2000;
  Eigen::VectorXd params = Eigen::Map<const Eigen::VectorXd>(p0.data(), p);
  const auto status = lm.minimize(params);

  FitResult result;
  result.params.assign(params.data(), params.data() + p);
  result.points = n;
  result.iterations = static_cast<long>(lm.njev);
  result.converged = status == Eigen::LevenbergMarquardtSpace::RelativeReductionTooSmall ||
                     status == Eigen::LevenbergMarquardtSpace::RelativeErrorTooSmall ||
                     status == Eigen::LevenbergMarquardtSpace::RelativeErrorAndReductionTooSmall ||
                     status == Eigen::LevenbergMarquardtSpace::CosinusTooSmall;
  result.status = status_name(status);

  Eigen::VectorXd f(n);
  functor(params, f);
  result.rss = f.squaredNorm();
  double mean_y = 0.0;
  for (double v : y) mean_y += v;
  mean_y /= static_cast<double>(n);
  double tss = 0.0;
  for (double v : y) tss += (v - mean_y) * (v - mean_y);
  result.r2 = tss > 0.0 ? 1.0 - result.rss / tss : (result.rss == 0.0 ? 1.0 : 0.0);

  // Covariance from the Jacobian at the solution (a fresh one, not MINPACK's QR factors).
  Eigen::MatrixXd jac(n, p);
  functor.df(params, jac);
  // Small products by hand (p is 2 or 3): Eigen's blocked GEMM trips a GCC 12
  // -Wmaybe-uninitialized false positive under -march=native with AVX-512.
  Eigen::MatrixXd jtj = Eigen::MatrixXd::Zero(p, p);
  for (long a = 0; a < p; ++a)
    for (long b = 0; b < p; ++b)
      for (long i = 0; i < n; ++i) jtj(a, b) += jac(i, a) * jac(i, b);
  const double s2 = result.rss / static_cast<double>(n - p);
  Eigen::MatrixXd ls_cov = Eigen::MatrixXd::Constant(p, p, std::numeric_limits<double>::infinity());
  Eigen::MatrixXd cov = ls_cov;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(jtj);
  if (lu.isInvertible()) {
    const Eigen::MatrixXd inv = lu.inverse();
    ls_cov = s2 * inv;
    cov = ls_cov;
    if (data_covariance) {
      if (data_covariance->size() != static_cast<std::size_t>(n))
        fail_input(
            fmt::format("fit: data covariance has {} rows for {} points: must be equal", data_covariance->size(), n));
      // meat = J^T Sigma J
      Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(p, p);
      for (long i = 0; i < n; ++i) {
        const auto& row = (*data_covariance)[i];
        if (row.size() != static_cast<std::size_t>(n))
          fail_input(fmt::format("fit: data covariance row {} has {} entries: must be {}", i, row.size(), n));
        for (long k = 0; k < n; ++k)
          for (long a = 0; a < p; ++a)
            for (long b = 0; b < p; ++b) meat(a, b) += jac(i, a) * row[k] * jac(k, b);
      }
      cov = Eigen::MatrixXd::Zero(p, p);
      for (long a = 0; a < p; ++a)
        for (long b = 0; b < p; ++b)
          for (long c = 0; c < p; ++c)
            for (long d = 0; d < p; ++d) cov(a, b) += inv(a, c) * meat(c, d) * inv(d, b);
    }
  }
  result.covariance.assign(p, std::vector<double>(p));
  result.std_errors.resize(p);
  result.ls_std_errors.resize(p);
  for (long i = 0; i < p; ++i) {
    for (long k = 0; k < p; ++k) result.covariance[i][k] = cov(i, k);
    result.std_errors[i] = std::sqrt(std::max(cov(i, i), 0.0));
    result.ls_std_errors[i] = std::sqrt(std::max(ls_cov(i, i), 0.0));
  }
  return result;
}

double pore_erf_model(double x, double a, double b) { return 1.0 - std::erf((x - b) / (a * std::numbers::sqrt2)); }

ErfFit fit_pore_erf(const std::vector<double>& x, const std::vector<double>& probability,
                    const std::vector<std::vector<double>>* data_covariance) {
  // Start: eq. 6 crosses P = 1/2 at b + 0.6745 a and P = 1/10 at b + 1.6449 a (erfc^-1 values
  // times sqrt 2). Linear interpolation of the data at those levels, x sorted ascending.
  auto crossing = [&](double level) {
    for (std::size_t i = 1; i < x.size(); ++i) {
      if ((probability[i - 1] - level) * (probability[i] - level) <= 0.0 && probability[i - 1] != probability[i]) {
        const double t = (probability[i - 1] - level) / (probability[i - 1] - probability[i]);
        return x[i - 1] + t * (x[i] - x[i - 1]);
      }
    }
    return std::numeric_limits<double>::quiet_NaN();
  };
  const double x50 = crossing(0.5), x10 = crossing(0.1);
  double a0 = 0.5, b0 = 0.0;
  if (std::isfinite(x50) && std::isfinite(x10) && x10 > x50) {
    a0 = (x10 - x50) / (1.6449 - 0.6745);
    b0 = x50 - 0.6745 * a0;
  } else if (!x.empty()) {
    a0 = std::max(0.25 * (x.back() - x.front()), 1e-3);
  }
  const FitModel model = [](double xi, const std::vector<double>& p, std::vector<double>* g) {
    const double a = p[0], b = p[1];
    const double z = (xi - b) / (a * std::numbers::sqrt2);
    if (g) {
      // d/dz (1 - erf z) = -2/sqrt(pi) exp(-z^2); dz/da = -z/a; dz/db = -1/(a sqrt 2).
      const double dpdz = -2.0 / std::sqrt(std::numbers::pi) * std::exp(-z * z);
      (*g)[0] = dpdz * (-z / a);
      (*g)[1] = dpdz * (-1.0 / (a * std::numbers::sqrt2));
    }
    return 1.0 - std::erf(z);
  };
  const FitResult r = fit_least_squares(model, x, probability, {a0, b0}, data_covariance);
  ErfFit fit;
  fit.a = r.params[0];
  fit.b = r.params[1];
  fit.a_err = r.std_errors[0];
  fit.b_err = r.std_errors[1];
  fit.a_ls_err = r.ls_std_errors[0];
  fit.b_ls_err = r.ls_std_errors[1];
  fit.r2 = r.r2;
  fit.points = r.points;
  fit.converged = r.converged && fit.a > 0.0;  // a < 0 would be a rising curve
  return fit;
}

}  // namespace packlab::analyze
