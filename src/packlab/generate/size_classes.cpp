#include "packlab/generate/size_classes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "packlab/core/error.hpp"

namespace packlab::generate {

SizeClasses SizeClasses::from_options(const std::vector<double>& sizes, const std::vector<double>& number_fractions,
                                      const std::vector<double>& volume_fractions) {
  if (!number_fractions.empty() && !volume_fractions.empty())
    fail_input("--number-fractions and --volume-fractions: give one of them");
  SizeClasses c;
  c.sizes = sizes;
  c.volume_fractions = !volume_fractions.empty();
  c.fractions = c.volume_fractions ? volume_fractions : number_fractions;
  c.validate();
  return c;
}

void SizeClasses::validate() const {
  require(!sizes.empty(), "sizes", 0, "a list of at least one relative diameter");
  for (double s : sizes) require(s > 0.0 && std::isfinite(s), "sizes", s, "> 0 (relative diameters)");
  if (!fractions.empty()) {
    require(fractions.size() == sizes.size(), volume_fractions ? "volume_fractions" : "number_fractions",
            static_cast<double>(fractions.size()), fmt::format("one value per size ({})", sizes.size()));
    double sum = 0.0;
    for (double f : fractions) {
      require(f >= 0.0 && std::isfinite(f), volume_fractions ? "volume_fractions" : "number_fractions", f, ">= 0");
      sum += f;
    }
    require(sum > 0.0, volume_fractions ? "volume_fractions" : "number_fractions", sum, "a positive sum");
  }
}

std::vector<double> SizeClasses::number_fractions() const {
  validate();
  std::vector<double> x(sizes.size(), 1.0);
  if (!fractions.empty()) {
    for (std::size_t k = 0; k < sizes.size(); ++k)
      x[k] = volume_fractions ? fractions[k] / (sizes[k] * sizes[k] * sizes[k]) : fractions[k];
  }
  const double sum = std::accumulate(x.begin(), x.end(), 0.0);
  for (double& v : x) v /= sum;
  return x;
}

std::vector<long> SizeClasses::counts(long n) const {
  const std::vector<double> x = number_fractions();
  std::vector<long> c(x.size());
  std::vector<std::pair<double, std::size_t>> rest;
  long total = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double exact = x[k] * static_cast<double>(n);
    c[k] = static_cast<long>(std::floor(exact));
    total += c[k];
    rest.emplace_back(exact - std::floor(exact), k);
  }
  std::stable_sort(rest.begin(), rest.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t r = 0; total < n; ++r, ++total) ++c[rest[r % rest.size()].second];
  return c;
}

}  // namespace packlab::generate
