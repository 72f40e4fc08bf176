// Coordination numbers (vem-void-expansion-method §2.2): particles i and j are in contact
// when their centre distance is below (1 + eps)(r_i + r_j). Like freud's analysis classes:
// configure, compute(packing), read plain arrays.
#pragma once

#include <cstddef>
#include <vector>

#include "packlab/core/packing.hpp"

namespace packlab::analyze {

class Coordination {
 public:
  explicit Coordination(double contact_eps = 0.01);

  void compute(const Packing& packing);

  // Contacts per particle (periodic images counted).
  const std::vector<int>& counts() const;
  // Mean over all particles.
  double mean() const;
  // Number of contacts (pairs).
  std::size_t contacts() const;
  double contact_eps() const { return contact_eps_; }

 private:
  void require_computed() const;
  double contact_eps_;
  bool computed_ = false;
  std::vector<int> counts_;
  std::size_t contacts_ = 0;
};

}  // namespace packlab::analyze
