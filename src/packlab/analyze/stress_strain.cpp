#include "packlab/analyze/stress_strain.hpp"

#include <algorithm>
#include <cmath>

namespace packlab::analyze {

ModulusFit fit_youngs_modulus(const std::vector<double>& strain, const std::vector<double>& stress,
                              double lower_fraction, double window_fraction) {
  ModulusFit fit;
  const std::size_t n = std::min(strain.size(), stress.size());
  if (n < 3) return fit;
  std::size_t peak = 0;
  for (std::size_t k = 1; k < n; ++k)
    if (stress[k] > stress[peak]) peak = k;
  const double smax = stress[peak];
  if (!(smax > 0.0)) return fit;
  const double lower = lower_fraction * smax, width = window_fraction * smax;
  for (std::size_t a = 0; a <= peak; ++a) {
    if (stress[a] < lower) continue;
    // The window: points a..b with stress[b] - stress[a] spanning `width` (monotone enough).
    std::size_t b = a;
    while (b < peak && stress[b] - stress[a] < width) ++b;
    if (stress[b] - stress[a] < width) break;  // the rest of the curve spans less than a window
    const std::size_t m = b - a + 1;
    if (m < 3) continue;
    double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
    for (std::size_t k = a; k <= b; ++k) {
      sx += strain[k];
      sy += stress[k];
      sxx += strain[k] * strain[k];
      sxy += strain[k] * stress[k];
      syy += stress[k] * stress[k];
    }
    const double dm = static_cast<double>(m);
    const double vx = sxx - sx * sx / dm, vxy = sxy - sx * sy / dm, vy = syy - sy * sy / dm;
    if (!(vx > 0.0)) continue;
    const double slope = vxy / vx;
    if (!fit.found || slope > fit.youngs_modulus) {
      fit.found = true;
      fit.youngs_modulus = slope;
      fit.intercept = (sy - slope * sx) / dm;
      fit.strain_begin = strain[a];
      fit.strain_end = strain[b];
      fit.points = static_cast<int>(m);
      fit.r2 = vy > 0.0 ? vxy * vxy / (vx * vy) : 1.0;
    }
  }
  return fit;
}

std::vector<TypeStress> stress_by_type(const Packing& model, const std::vector<std::array<double, 9>>& stress) {
  int types = 0;
  for (int t : model.type) types = std::max(types, t + 1);
  std::vector<TypeStress> out(static_cast<std::size_t>(types));
  std::vector<std::array<double, 3>> sum(out.size(), std::array<double, 3>{}), sum2(out.size(), std::array<double, 3>{});
  for (std::size_t k = 0; k < model.size() && k < stress.size(); ++k) {
    if (!model.fixed.empty() && model.fixed[k]) continue;
    const auto t = static_cast<std::size_t>(model.type[k]);
    ++out[t].particles;
    for (int a = 0; a < 3; ++a) {
      const double s = stress[k][static_cast<std::size_t>(4 * a)];
      sum[t][static_cast<std::size_t>(a)] += s;
      sum2[t][static_cast<std::size_t>(a)] += s * s;
    }
  }
  std::vector<TypeStress> kept;
  for (std::size_t t = 0; t < out.size(); ++t) {
    out[t].type = static_cast<int>(t);
    if (out[t].particles == 0) continue;
    const double n = static_cast<double>(out[t].particles);
    for (std::size_t a = 0; a < 3; ++a) {
      out[t].mean[a] = sum[t][a] / n;
      out[t].sd[a] = n > 1 ? std::sqrt(std::max(0.0, (sum2[t][a] - n * out[t].mean[a] * out[t].mean[a]) / (n - 1))) : 0.0;
    }
    kept.push_back(out[t]);
  }
  return kept;
}

std::vector<std::size_t> histogram(const std::vector<double>& values, double lo, double hi, int bins) {
  std::vector<std::size_t> counts(static_cast<std::size_t>(std::max(bins, 1)), 0);
  if (!(hi > lo)) return counts;
  for (double v : values) {
    if (!std::isfinite(v) || v < lo || v > hi) continue;
    auto k = static_cast<long>((v - lo) / (hi - lo) * bins);
    k = std::clamp(k, 0L, static_cast<long>(bins) - 1);
    ++counts[static_cast<std::size_t>(k)];
  }
  return counts;
}

}  // namespace packlab::analyze
