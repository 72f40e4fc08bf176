#include "packlab/analyze/fabric.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "packlab/analyze/coordination.hpp"
#include "packlab/core/error.hpp"

namespace packlab::analyze {

Fabric::Fabric(double contact_eps, int bins, bool exclude_rattlers, int rattler_threshold)
    : contact_eps_(contact_eps),
      bins_(bins),
      exclude_rattlers_(exclude_rattlers),
      rattler_threshold_(rattler_threshold) {
  require(contact_eps >= 0.0 && contact_eps < 1.0, "contact_eps", contact_eps, "in [0, 1)");
  require(bins >= 1 && bins <= 10000, "fabric_bins", bins, "an integer in [1, 10000]");
}

void Fabric::compute(const Packing& packing, bool reset) {
  if (reset || !computed_) {
    contacts_ = 0;
    sum_ = {};
    counts_.assign(bins_, {0, 0, 0});
  }
  const ContactList list = find_contacts(packing, contact_eps_);
  std::vector<std::uint8_t> rattler;
  if (exclude_rattlers_) {
    Coordination cn(contact_eps_, rattler_threshold_);
    cn.compute(packing);
    rattler = cn.rattlers();
  }
  for (std::size_t c = 0; c < list.size(); ++c) {
    if (exclude_rattlers_ && (rattler[list.i[c]] || rattler[list.j[c]])) continue;
    const double len = norm(list.branch[c]);
    if (len <= 0.0) continue;  // coincident centres have no normal
    const Vec3 n = list.branch[c] * (1.0 / len);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) sum_[a][b] += n[a] * n[b];
    for (int a = 0; a < 3; ++a) {
      const int bin = std::min(bins_ - 1, static_cast<int>(std::abs(n[a]) * bins_));
      ++counts_[bin][a];
    }
    ++contacts_;
  }
  tensor_ = {};
  if (contacts_ > 0)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) tensor_[a][b] = sum_[a][b] / static_cast<double>(contacts_);
  density_.assign(bins_, {0.0, 0.0, 0.0});
  if (contacts_ > 0)
    for (int k = 0; k < bins_; ++k)
      for (int a = 0; a < 3; ++a)
        density_[k][a] = static_cast<double>(counts_[k][a]) * bins_ / static_cast<double>(contacts_);
  computed_ = true;
}

void Fabric::require_computed() const {
  if (!computed_) throw std::logic_error("Fabric: compute() must be called before reading results");
}

const Fabric::Matrix3& Fabric::tensor() const {
  require_computed();
  return tensor_;
}

Fabric::Matrix3 Fabric::deviator() const {
  require_computed();
  Matrix3 d = tensor_;
  const double third = (tensor_[0][0] + tensor_[1][1] + tensor_[2][2]) / 3.0;
  for (int a = 0; a < 3; ++a) d[a][a] -= third;
  return d;
}

std::array<double, 3> Fabric::eigenvalues() const {
  require_computed();
  Eigen::Matrix3d m;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) m(a, b) = tensor_[a][b];
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(m, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d& ev = solver.eigenvalues();  // ascending
  return {ev[2], ev[1], ev[0]};
}

double Fabric::anisotropy() const {
  const Matrix3 d = deviator();
  double s = 0.0;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) s += (7.5 * d[a][b]) * (7.5 * d[a][b]);
  return std::sqrt(1.5 * s);
}

long Fabric::contacts() const {
  require_computed();
  return contacts_;
}

const std::vector<std::array<double, 3>>& Fabric::normal_density() const {
  require_computed();
  return density_;
}

std::vector<double> Fabric::bin_centers() const {
  std::vector<double> c(bins_);
  for (int k = 0; k < bins_; ++k) c[k] = (k + 0.5) / bins_;
  return c;
}

}  // namespace packlab::analyze
