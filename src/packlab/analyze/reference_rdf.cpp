#include "packlab/analyze/reference_rdf.hpp"

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

}  // namespace packlab::analyze::reference
