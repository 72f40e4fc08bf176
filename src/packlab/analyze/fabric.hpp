// Contact fabric: the second-order fabric tensor F_ij = <n_i n_j> over contacts (unit branch
// vectors n, each contact once; trace 1, F = I/3 for an isotropic network), its deviator
// and scalar anisotropy, and the distribution of contact normals.
//
// Anisotropy follows the usual second-order Fourier approximation of the normal density
// E(n) = (1 + a_ij n_i n_j) / (4 pi) with a_ij = 15/2 (F_ij - delta_ij/3), and the scalar
// a = sqrt(3/2 a_ij a_ij) (0 isotropic, 7.5 for all normals along one axis).
// Normal distribution: for each box axis e, the density of |n . e| on [0, 1] (uniform = 1 for
// isotropic normals; for e = z it is the density of the cosine of the polar angle). Contacts are those of
// Coordination (d < (1 + eps)(r_i + r_j)); contacts of rattlers can be left out.
#pragma once

#include <array>
#include <vector>

#include "packlab/core/packing.hpp"

namespace packlab::analyze {

class Fabric {
 public:
  explicit Fabric(double contact_eps = 0.01, int bins = 18, bool exclude_rattlers = false, int rattler_threshold = 4);

  // reset = false accumulates contacts over several packings (realizations).
  void compute(const Packing& packing, bool reset = true);

  using Matrix3 = std::array<std::array<double, 3>, 3>;
  const Matrix3& tensor() const;              // F_ij, trace 1
  Matrix3 deviator() const;                   // F - I/3
  std::array<double, 3> eigenvalues() const;  // of F, descending
  double anisotropy() const;                  // sqrt(3/2 a:a), a = 15/2 dev F
  long contacts() const;                      // contacts used (all frames)
  // density[axis][bin] of |n . e_axis| over bins of width 1/bins on [0, 1]; 1 = isotropic.
  const std::vector<std::array<double, 3>>& normal_density() const;
  // Bin centres of |cos| for normal_density().
  std::vector<double> bin_centers() const;
  int bins() const { return bins_; }

 private:
  void require_computed() const;
  double contact_eps_;
  int bins_;
  bool exclude_rattlers_;
  int rattler_threshold_;
  bool computed_ = false;
  long contacts_ = 0;
  Matrix3 sum_{};
  Matrix3 tensor_{};
  std::vector<std::array<long, 3>> counts_;
  std::vector<std::array<double, 3>> density_;
};

}  // namespace packlab::analyze
