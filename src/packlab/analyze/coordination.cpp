#include "packlab/analyze/coordination.hpp"

#include <algorithm>
#include <stdexcept>

#include "packlab/core/error.hpp"
#include "packlab/core/neighbor_list.hpp"

namespace packlab::analyze {

ContactList find_contacts(const Packing& packing, double contact_eps, int threads) {
  require(contact_eps >= 0.0 && contact_eps < 1.0, "contact_eps", contact_eps, "in [0, 1)");
  packing.validate();
  const std::size_t n = packing.size();
  std::vector<Vec3> position = packing.position;
  double r_max = 0.0;
  for (double r : packing.radius) r_max = std::max(r_max, r);
  // The list holds every pair with d < r_i + r_j + skin; eps (r_i + r_j) <= 2 eps r_max.
  NeighborList list(2.0 * contact_eps * r_max * (1.0 + 1e-12) + 1e-300);
  list.build(packing.box, position, packing.radius, threads);
  ContactList contacts;
  for (std::size_t i = 0; i < n; ++i) {
    for (int p = list.first(static_cast<int>(i)); p < list.first(static_cast<int>(i) + 1); ++p) {
      const int j = list.partner()[p];
      const Vec3 d = position[j] + list.image_offset(list.image()[p]) - position[i];
      const double cut = (1.0 + contact_eps) * (packing.radius[i] + packing.radius[j]);
      if (norm2(d) < cut * cut) {
        contacts.i.push_back(static_cast<int>(i));
        contacts.j.push_back(j);
        contacts.branch.push_back(d);
      }
    }
  }
  return contacts;
}

RattlerRule rattler_rule_from_name(const std::string& name) {
  if (name == "iterative") return RattlerRule::iterative;
  if (name == "single_pass") return RattlerRule::single_pass;
  fail_input("rattler_rule = " + name + ": must be iterative or single_pass");
}

std::string rattler_rule_name(RattlerRule rule) { return rule == RattlerRule::iterative ? "iterative" : "single_pass"; }

Coordination::Coordination(double contact_eps, int rattler_threshold, RattlerRule rattler_rule)
    : contact_eps_(contact_eps), rattler_threshold_(rattler_threshold), rattler_rule_(rattler_rule) {
  require(contact_eps >= 0.0 && contact_eps < 1.0, "contact_eps", contact_eps, "in [0, 1)");
  require(rattler_threshold >= 0 && rattler_threshold <= 64, "rattler_threshold", rattler_threshold,
          "an integer in [0, 64]");
}

std::size_t Coordination::type_slot(int type) {
  const auto it = std::lower_bound(types_.begin(), types_.end(), type);
  const auto slot = static_cast<std::size_t>(it - types_.begin());
  if (it != types_.end() && *it == type) return slot;
  types_.insert(it, type);
  type_particles_.insert(type_particles_.begin() + static_cast<long>(slot), 0);
  type_rattlers_.insert(type_rattlers_.begin() + static_cast<long>(slot), 0);
  for (auto& row : type_contact_ends_) row.insert(row.begin() + static_cast<long>(slot), 0);
  type_contact_ends_.insert(type_contact_ends_.begin() + static_cast<long>(slot), std::vector<long>(types_.size(), 0));
  return slot;
}

void Coordination::compute(const Packing& packing, bool reset) {
  const ContactList list = find_contacts(packing, contact_eps_);
  const std::size_t n = packing.size();
  if (reset || !computed_) {
    frames_ = 0;
    particles_ = rattler_total_ = contact_ends_ = non_rattler_contact_ends_ = 0;
    distribution_.clear();
    types_.clear();
    type_particles_.clear();
    type_rattlers_.clear();
    type_contact_ends_.clear();
  }
  counts_.assign(n, 0);
  contacts_ = list.size();
  for (std::size_t c = 0; c < list.size(); ++c) {
    ++counts_[list.i[c]];
    ++counts_[list.j[c]];
  }

  // Rattlers: fewer than the threshold; iteratively, contacts with rattlers stop counting.
  rattlers_.assign(n, 0);
  std::vector<int> live = counts_;
  for (std::size_t k = 0; k < n; ++k) rattlers_[k] = live[k] < rattler_threshold_ ? 1 : 0;
  if (rattler_rule_ == RattlerRule::iterative) {
    // Adjacency in CSR form to propagate removals.
    std::vector<int> start(n + 1, 0), adj(2 * list.size());
    for (std::size_t c = 0; c < list.size(); ++c) {
      ++start[list.i[c] + 1];
      ++start[list.j[c] + 1];
    }
    for (std::size_t k = 0; k < n; ++k) start[k + 1] += start[k];
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (std::size_t c = 0; c < list.size(); ++c) {
      adj[fill[list.i[c]]++] = list.j[c];
      adj[fill[list.j[c]]++] = list.i[c];
    }
    std::vector<int> queue;
    for (std::size_t k = 0; k < n; ++k)
      if (rattlers_[k]) queue.push_back(static_cast<int>(k));
    while (!queue.empty()) {
      const int k = queue.back();
      queue.pop_back();
      for (int e = start[k]; e < start[k + 1]; ++e) {
        const int m = adj[e];
        --live[m];
        if (!rattlers_[m] && live[m] < rattler_threshold_) {
          rattlers_[m] = 1;
          queue.push_back(m);
        }
      }
    }
  }

  // Statistics.
  ++frames_;
  particles_ += static_cast<long>(n);
  // Register every type first: inserting one shifts the slots of the larger ones.
  for (std::size_t k = 0; k < n; ++k) (void)type_slot(packing.type[k]);
  std::vector<std::size_t> slot(n);
  for (std::size_t k = 0; k < n; ++k) {
    slot[k] = type_slot(packing.type[k]);
    ++type_particles_[slot[k]];
    contact_ends_ += counts_[k];
    if (rattlers_[k]) {
      ++rattler_total_;
      ++type_rattlers_[slot[k]];
    }
    if (static_cast<std::size_t>(counts_[k]) >= distribution_.size()) distribution_.resize(counts_[k] + 1, 0);
    ++distribution_[counts_[k]];
  }
  for (std::size_t c = 0; c < list.size(); ++c) {
    const int a = list.i[c], b = list.j[c];
    ++type_contact_ends_[slot[a]][slot[b]];
    ++type_contact_ends_[slot[b]][slot[a]];
    if (!rattlers_[a] && !rattlers_[b]) non_rattler_contact_ends_ += 2;
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

const std::vector<std::uint8_t>& Coordination::rattlers() const {
  require_computed();
  return rattlers_;
}

std::size_t Coordination::contacts() const {
  require_computed();
  return contacts_;
}

double Coordination::mean() const {
  require_computed();
  return particles_ == 0 ? 0.0 : static_cast<double>(contact_ends_) / static_cast<double>(particles_);
}

double Coordination::mean_without_rattlers() const {
  require_computed();
  const long kept = particles_ - rattler_total_;
  return kept == 0 ? 0.0 : static_cast<double>(non_rattler_contact_ends_) / static_cast<double>(kept);
}

std::size_t Coordination::rattler_count() const {
  require_computed();
  return static_cast<std::size_t>(rattler_total_);
}

std::size_t Coordination::particle_count() const {
  require_computed();
  return static_cast<std::size_t>(particles_);
}

long Coordination::frames() const {
  require_computed();
  return frames_;
}

const std::vector<long>& Coordination::distribution() const {
  require_computed();
  return distribution_;
}

const std::vector<int>& Coordination::types() const {
  require_computed();
  return types_;
}

std::vector<double> Coordination::mean_by_type() const {
  require_computed();
  std::vector<double> m(types_.size(), 0.0);
  for (std::size_t a = 0; a < types_.size(); ++a) {
    long ends = 0;
    for (long e : type_contact_ends_[a]) ends += e;
    m[a] = type_particles_[a] ? static_cast<double>(ends) / static_cast<double>(type_particles_[a]) : 0.0;
  }
  return m;
}

const std::vector<long>& Coordination::particles_by_type() const {
  require_computed();
  return type_particles_;
}

const std::vector<long>& Coordination::rattlers_by_type() const {
  require_computed();
  return type_rattlers_;
}

std::vector<std::vector<double>> Coordination::between_types() const {
  require_computed();
  std::vector<std::vector<double>> z(types_.size(), std::vector<double>(types_.size(), 0.0));
  for (std::size_t a = 0; a < types_.size(); ++a)
    for (std::size_t b = 0; b < types_.size(); ++b)
      z[a][b] = type_particles_[a]
                    ? static_cast<double>(type_contact_ends_[a][b]) / static_cast<double>(type_particles_[a])
                    : 0.0;
  return z;
}

}  // namespace packlab::analyze
