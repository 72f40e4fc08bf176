#include "packlab/analyze/porosity_laws.hpp"

#include <fmt/format.h>

#include <cmath>

#include "packlab/analyze/fits.hpp"
#include "packlab/core/error.hpp"

namespace packlab::analyze {

PorosityLaw porosity_law_from_name(const std::string& name) {
  if (name == "exponential") return PorosityLaw::exponential;
  if (name == "power") return PorosityLaw::power;
  fail_input(fmt::format("porosity law = {}: must be 'exponential' (eq. 22) or 'power' (eq. 23)", name));
}

std::string porosity_law_name(PorosityLaw law) { return law == PorosityLaw::exponential ? "exponential" : "power"; }

namespace {
// The law's log-linear variable: log y = log E0 - exponent * u(eps).
double log_variable(PorosityLaw law, double eps) { return law == PorosityLaw::exponential ? eps : -std::log1p(-eps); }
}  // namespace

double PorosityFit::model(double porosity) const { return e0 * std::exp(-exponent * log_variable(law, porosity)); }

PorosityFit fit_porosity_law(PorosityLaw law, const std::vector<double>& porosity, const std::vector<double>& value,
                             double fixed_e0) {
  if (porosity.size() != value.size())
    fail_input(fmt::format("porosity fit: {} porosities but {} values", porosity.size(), value.size()));
  const bool free_e0 = !(fixed_e0 > 0.0);
  const std::size_t min_points = free_e0 ? 3 : 2;
  if (porosity.size() < min_points)
    fail_input(fmt::format("porosity fit: {} points, needs at least {}", porosity.size(), min_points));
  for (std::size_t k = 0; k < porosity.size(); ++k) {
    require(porosity[k] >= 0.0 && porosity[k] < 1.0, "porosity", porosity[k], "in [0, 1)");
    require(value[k] > 0.0 && std::isfinite(value[k]), "value", value[k], "> 0");
  }
  // Start: least squares of log y on u.
  const std::size_t n = porosity.size();
  double su = 0, sl = 0, suu = 0, sul = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double u = log_variable(law, porosity[k]), l = std::log(value[k]);
    su += u;
    sl += l;
    suu += u * u;
    sul += u * l;
  }
  const double dn = static_cast<double>(n);
  double exponent0 = 0.0, log_e0 = std::log(fixed_e0 > 0.0 ? fixed_e0 : 1.0);
  if (free_e0) {
    const double var = suu - su * su / dn;
    exponent0 = var > 0.0 ? -(sul - su * sl / dn) / var : 1.0;
    log_e0 = (sl + exponent0 * su) / dn;
  } else {
    exponent0 = suu > 0.0 ? (su * log_e0 - sul) / suu : 1.0;
  }
  PorosityFit out;
  out.law = law;
  out.points = static_cast<long>(n);
  FitResult fit;
  // Values in units of their geometric mean, so that E0 and the exponent are of order one in
  // the least-squares problem (Pa-sized E0 makes J^T J numerically singular).
  const double unit = std::exp(sl / dn);
  std::vector<double> scaled(value);
  for (double& v : scaled) v /= unit;
  if (free_e0) {
    const FitModel model = [law](double eps, const std::vector<double>& p, std::vector<double>* g) {
      const double u = log_variable(law, eps);
      const double e = std::exp(-p[1] * u);
      if (g) {
        (*g)[0] = e;
        (*g)[1] = -p[0] * u * e;
      }
      return p[0] * e;
    };
    fit = fit_least_squares(model, porosity, scaled, {std::exp(log_e0) / unit, exponent0});
    out.e0 = fit.params[0] * unit;
    out.exponent = fit.params[1];
    out.e0_err = fit.std_errors[0] * unit;
    out.exponent_err = fit.std_errors[1];
  } else {
    const double e0_scaled = fixed_e0 / unit;
    const FitModel model = [law, e0_scaled](double eps, const std::vector<double>& p, std::vector<double>* g) {
      const double u = log_variable(law, eps);
      const double e = std::exp(-p[0] * u);
      if (g) (*g)[0] = -e0_scaled * u * e;
      return e0_scaled * e;
    };
    fit = fit_least_squares(model, porosity, scaled, {exponent0});
    out.e0 = fixed_e0;
    out.exponent = fit.params[0];
    out.exponent_err = fit.std_errors[0];
  }
  out.rss = fit.rss * unit * unit;
  out.r2 = fit.r2;
  out.converged = fit.converged;
  double rel = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double d = (value[k] - out.model(porosity[k])) / value[k];
    rel += d * d;
  }
  out.rms_relative = std::sqrt(rel / dn);
  return out;
}

}  // namespace packlab::analyze
