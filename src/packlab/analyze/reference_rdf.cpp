#include "packlab/analyze/reference_rdf.hpp"

#include <array>
#include <cmath>
#include <numbers>

#include "packlab/core/error.hpp"

namespace packlab::analyze::reference {

double well_stirred(double r, double a) { return r >= 2.0 * a ? 1.0 : 0.0; }

double willis_shape(double r_over_a) {
  return std::cos(std::numbers::pi * r_over_a) * std::exp(2.0 * (2.0 - r_over_a));
}

double willis_contact_original(double c) {
  require(c > 0.125 && c < 1.0, "c", c, "in (1/8, 1) for Willis's contact term, eq. (12_1)");
  return 0.8006 * (8.0 * c - 1.0) / c;
}

double percus_yevick_contact(double c) {
  require(c >= 0.0 && c < 1.0, "c", c, "in [0, 1)");
  return (1.0 + 0.5 * c) / ((1.0 - c) * (1.0 - c));
}

double willis(double r, double a, double c, bool use_original) {
  if (r < 2.0 * a) return 0.0;
  const double gc = use_original ? willis_contact_original(c) : percus_yevick_contact(c) - 1.0;
  return 1.0 + gc * willis_shape(r / a);
}

std::vector<std::vector<double>> percus_yevick_contact_mixture(const std::vector<double>& radius,
                                                               const std::vector<double>& volume_fraction) {
  if (radius.size() != volume_fraction.size() || radius.empty())
    fail_input("Percus-Yevick mixture: one volume fraction per radius is needed");
  double xi2 = 0.0, xi3 = 0.0;
  for (std::size_t k = 0; k < radius.size(); ++k) {
    require(radius[k] > 0.0, "radius", radius[k], "> 0");
    require(volume_fraction[k] >= 0.0, "volume_fraction", volume_fraction[k], ">= 0");
    const double d = 2.0 * radius[k];
    // n_k = c_k / (pi d^3 / 6): xi3 += c_k, xi2 += c_k / d.
    xi3 += volume_fraction[k];
    xi2 += volume_fraction[k] / d;
  }
  require(xi3 < 1.0, "total volume fraction", xi3, "< 1");
  std::vector<std::vector<double>> g(radius.size(), std::vector<double>(radius.size()));
  for (std::size_t i = 0; i < radius.size(); ++i)
    for (std::size_t j = 0; j < radius.size(); ++j) {
      const double di = 2.0 * radius[i], dj = 2.0 * radius[j];
      // sigma_ij = (d_i + d_j) / 2 is the contact distance.
      g[i][j] = 1.0 / (1.0 - xi3) + 1.5 * (di * dj / (0.5 * (di + dj))) * xi2 / ((1.0 - xi3) * (1.0 - xi3));
    }
  return g;
}

double percus_yevick_contact_dilute(double c, double lambda) {
  require(c >= 0.0 && c < 1.0, "c", c, "in [0, 1)");
  require(lambda > 0.0, "lambda", lambda, "> 0");
  return (1.0 + c * (2.0 * lambda - 1.0) / (lambda + 1.0)) / ((1.0 - c) * (1.0 - c));
}

double willis_partial(double scaled_r, double contact_value) {
  if (scaled_r < 2.0) return 0.0;
  return 1.0 + (contact_value - 1.0) * willis_shape(scaled_r);
}

namespace {

// Wertheim's c(x) = -alpha - beta x - gamma x^3 inside the core, x = r / sigma < 1 (sigma = 2a).
struct PyDirect {
  double alpha, beta, gamma;
  explicit PyDirect(double eta) {
    const double d = std::pow(1.0 - eta, 4);
    alpha = (1.0 + 2.0 * eta) * (1.0 + 2.0 * eta) / d;
    beta = -6.0 * eta * (1.0 + 0.5 * eta) * (1.0 + 0.5 * eta) / d;
    gamma = 0.5 * eta * alpha;
  }
  double operator()(double x) const { return x < 1.0 ? -alpha - beta * x - gamma * x * x * x : 0.0; }
};

// I_n(k) = integral_0^1 x^n sin(k x) dx for n = 1, 2, 4: closed forms, or their Taylor series
// where the closed forms cancel (k < 1).
std::array<double, 3> sine_moments(double k) {
  if (k < 1.0) {
    std::array<double, 3> sum{0.0, 0.0, 0.0};
    double term = k;  // (-1)^m k^(2m+1) / (2m+1)!
    for (int m = 0; m < 12; ++m) {
      sum[0] += term / (2 * m + 3);
      sum[1] += term / (2 * m + 4);
      sum[2] += term / (2 * m + 6);
      term *= -k * k / ((2.0 * m + 2.0) * (2.0 * m + 3.0));
    }
    return sum;
  }
  const double s = std::sin(k), c = std::cos(k), k2 = k * k;
  return {(s - k * c) / k2, (2.0 * k * s - (k2 - 2.0) * c - 2.0) / (k2 * k),
          ((4.0 * k2 * k - 24.0 * k) * s - (k2 * k2 - 12.0 * k2 + 24.0) * c + 24.0) / (k2 * k2 * k)};
}

}  // namespace

std::vector<double> percus_yevick_total_correlation(const std::vector<double>& r_over_a, double c) {
  require(c >= 0.0 && c < 1.0, "c", c, "in [0, 1)");
  const PyDirect direct(c);
  const double rho = 6.0 * c / std::numbers::pi;  // number density, sigma = 1
  // gamma^(k) = rho c^(k)^2 / (1 - rho c^(k)) on a uniform grid; it falls as k^-4, so the sine
  // transform of k gamma^(k) is cut at k_max = 400 (error ~1e-8); dk = 0.004 resolves the
  // oscillations of sin(k x) for x up to ~50 sigma.
  constexpr double dk = 0.004, k_max = 400.0;
  const int nk = static_cast<int>(k_max / dk);
  std::vector<double> weight(static_cast<std::size_t>(nk + 1));
  for (int j = 0; j <= nk; ++j) {
    const double k = j * dk;
    double ck;  // c^(k) = 4 pi / k integral_0^1 c(x) x sin(k x) dx; its k -> 0 limit at k = 0
    if (j == 0) {
      ck = 4.0 * std::numbers::pi * (-direct.alpha / 3.0 - direct.beta / 4.0 - direct.gamma / 6.0);
    } else {
      const auto m = sine_moments(k);
      ck = 4.0 * std::numbers::pi / k * (-direct.alpha * m[0] - direct.beta * m[1] - direct.gamma * m[2]);
    }
    const double gk = rho * ck * ck / (1.0 - rho * ck);
    // Simpson weights (nk even) times k gamma^(k); the 1 / (2 pi^2 x) comes below.
    const double simpson = (j == 0 || j == nk) ? 1.0 : (j % 2 == 1 ? 4.0 : 2.0);
    weight[static_cast<std::size_t>(j)] = simpson * dk / 3.0 * k * gk;
  }
  std::vector<double> h(r_over_a.size());
  for (std::size_t i = 0; i < r_over_a.size(); ++i) {
    const double x = 0.5 * r_over_a[i];
    require(x > 0.0, "r_over_a", r_over_a[i], "> 0");
    // sin(j dk x) by the angle-addition recurrence (rounding grows ~ nk eps ~ 1e-11).
    const double step_sin = std::sin(dk * x), step_cos = std::cos(dk * x);
    double sn = 0.0, cs = 1.0, sum = 0.0;
    for (int j = 0; j <= nk; ++j) {
      sum += weight[static_cast<std::size_t>(j)] * sn;
      const double next = sn * step_cos + cs * step_sin;
      cs = cs * step_cos - sn * step_sin;
      sn = next;
    }
    const double indirect = sum / (2.0 * std::numbers::pi * std::numbers::pi * x);
    h[i] = indirect + direct(x);
  }
  return h;
}

std::vector<double> percus_yevick(const std::vector<double>& r_over_a, double c) {
  std::vector<double> g = percus_yevick_total_correlation(r_over_a, c);
  for (std::size_t i = 0; i < g.size(); ++i) g[i] = r_over_a[i] < 2.0 ? 0.0 : 1.0 + g[i];
  return g;
}

}  // namespace packlab::analyze::reference
