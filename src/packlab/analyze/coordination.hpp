// Coordination numbers (vem-void-expansion-method §2.2): particles i and j are in contact
// when their centre distance is below (1 + eps)(r_i + r_j). Like freud's analysis classes:
// configure, compute(packing), read plain arrays.
//
// Definitions (every one a named option, docs/analysis.md):
//  - contact: d_ij < (1 + contact_eps)(r_i + r_j), periodic images included (a particle can
//    touch its own image in a small box); overlapping pairs are contacts like any other;
//  - rattler: a particle with fewer than `rattler_threshold` contacts (default 4, the
//    d + 1 needed to hold a frictionless sphere in 3D). RattlerRule::iterative removes
//    rattlers repeatedly (their contacts no longer count for their neighbours) until every
//    remaining particle has at least the threshold: the k-core of the contact network, the
//    usual definition for jammed packings. RattlerRule::single_pass flags particles once;
//  - mean_without_rattlers: mean number of contacts between non-rattlers per non-rattler.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "packlab/core/packing.hpp"

namespace packlab::analyze {

// Contacts by the criterion above, each pair once (i <= j; i == j is a periodic self image).
struct ContactList {
  std::vector<int> i, j;
  std::vector<Vec3> branch;  // r_j + image shift - r_i [m]
  std::size_t size() const { return i.size(); }
};

ContactList find_contacts(const Packing& packing, double contact_eps, int threads = 1);

enum class RattlerRule { iterative, single_pass };
RattlerRule rattler_rule_from_name(const std::string& name);  // "iterative" | "single_pass"
std::string rattler_rule_name(RattlerRule rule);

class Coordination {
 public:
  explicit Coordination(double contact_eps = 0.01, int rattler_threshold = 4,
                        RattlerRule rattler_rule = RattlerRule::iterative);

  // reset = false adds this packing to the statistics of the previous ones (realizations);
  // the per-particle arrays always describe the last packing.
  void compute(const Packing& packing, bool reset = true);

  // --- last packing ---
  // Contacts per particle (periodic images counted).
  const std::vector<int>& counts() const;
  // 1 for rattlers.
  const std::vector<std::uint8_t>& rattlers() const;
  // Number of contacts (pairs).
  std::size_t contacts() const;

  // --- accumulated over the packings since the last reset ---
  // Mean over all particles.
  double mean() const;
  // Mean contacts among non-rattlers per non-rattler (0 when every particle rattles).
  double mean_without_rattlers() const;
  std::size_t rattler_count() const;
  std::size_t particle_count() const;
  long frames() const;
  // distribution()[k] = number of particles with k contacts.
  const std::vector<long>& distribution() const;
  // Particle types present (ascending) and, per type, the mean contacts (with any type), the
  // particle and rattler counts; between_types()[a][b] = mean number of contacts with
  // particles of type types()[b] per particle of type types()[a] (rows sum to the means).
  const std::vector<int>& types() const;
  std::vector<double> mean_by_type() const;
  const std::vector<long>& particles_by_type() const;
  const std::vector<long>& rattlers_by_type() const;
  std::vector<std::vector<double>> between_types() const;

  double contact_eps() const { return contact_eps_; }
  int rattler_threshold() const { return rattler_threshold_; }
  RattlerRule rattler_rule() const { return rattler_rule_; }

 private:
  void require_computed() const;
  std::size_t type_slot(int type);
  double contact_eps_;
  int rattler_threshold_;
  RattlerRule rattler_rule_;
  bool computed_ = false;
  // last packing
  std::vector<int> counts_;
  std::vector<std::uint8_t> rattlers_;
  std::size_t contacts_ = 0;
  // accumulated
  long frames_ = 0;
  long particles_ = 0, rattler_total_ = 0;
  long contact_ends_ = 0;              // sum of counts
  long non_rattler_contact_ends_ = 0;  // sum over non-rattlers of contacts with non-rattlers
  std::vector<long> distribution_;
  std::vector<int> types_;
  std::vector<long> type_particles_, type_rattlers_;
  std::vector<std::vector<long>> type_contact_ends_;  // [a][b]: contact ends at a-particles with b partners
};

}  // namespace packlab::analyze
