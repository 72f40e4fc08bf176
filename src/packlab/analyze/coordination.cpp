#include "packlab/analyze/coordination.hpp"

#include <algorithm>
#include <stdexcept>

#include "packlab/core/error.hpp"
#include "packlab/core/neighbor_list.hpp"

namespace packlab::analyze {

Coordination::Coordination(double contact_eps) : contact_eps_(contact_eps) {
  require(contact_eps >= 0.0 && contact_eps < 1.0, "contact_eps", contact_eps, "in [0, 1)");
}

void Coordination::compute(const Packing& packing) {
  packing.validate();
  const std::size_t n = packing.size();
  std::vector<Vec3> position = packing.position;
  double r_max = 0.0;
  for (double r : packing.radius) r_max = std::max(r_max, r);
  // The list holds every pair with d < r_i + r_j + skin; eps (r_i + r_j) <= 2 eps r_max.
  NeighborList list(2.0 * contact_eps_ * r_max * (1.0 + 1e-12) + 1e-300);
  list.build(packing.box, position, packing.radius);
  counts_.assign(n, 0);
  contacts_ = 0;
  for (std::size_t i = 0; i < n; ++i) {
    for (int p = list.first(static_cast<int>(i)); p < list.first(static_cast<int>(i) + 1); ++p) {
      const int j = list.partner()[p];
      const Vec3 d = position[j] + list.image_offset(list.image()[p]) - position[i];
      const double cut = (1.0 + contact_eps_) * (packing.radius[i] + packing.radius[j]);
      if (norm2(d) < cut * cut) {
        ++counts_[i];
        ++counts_[j];
        ++contacts_;
      }
    }
  }
  computed_ = true;
}

void Coordination::require_computed() const {
  if (!computed_) throw std::logic_error("Coordination: compute() must be called before reading results");
}

const std::vector<int>& Coordination::counts() const {
  require_computed();
  return counts_;
}

double Coordination::mean() const {
  require_computed();
  return counts_.empty() ? 0.0 : 2.0 * static_cast<double>(contacts_) / static_cast<double>(counts_.size());
}

std::size_t Coordination::contacts() const {
  require_computed();
  return contacts_;
}

}  // namespace packlab::analyze
