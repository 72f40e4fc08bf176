// Evaluation of mechanical tests: the Young's modulus and the strength of a stress-strain
// curve, per-type statistics of per-particle stresses, histograms.
//
// Young's modulus (the "linear slope of the stress-strain diagram", bpm-inverse-opals §3.1.2),
// method "max_tangent": least-squares slopes over sliding windows that each span
// `window_fraction` x the peak stress, on the points before the peak with stress >=
// `lower_fraction` x peak; E is the largest such slope (the plateau of the tangent modulus,
// Fig. 10's region 2, past the initial plate-contact toe and before damage softens the curve).
// Strength: the peak stress.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "packlab/core/packing.hpp"

namespace packlab::analyze {

struct ModulusFit {
  double youngs_modulus = 0.0;  // slope [Pa]
  double intercept = 0.0;       // [Pa]
  double strain_begin = 0.0, strain_end = 0.0;  // window of the fit
  double r2 = 0.0;
  int points = 0;
  bool found = false;
};

// Mean and standard deviation of the per-particle stress of one particle type (free particles).
struct TypeStress {
  int type = 0;
  std::size_t particles = 0;
  std::array<double, 3> mean{};  // sigma_xx, sigma_yy, sigma_zz [Pa], tension positive
  std::array<double, 3> sd{};
};

// The "max_tangent" modulus of a stress-strain curve (see the header comment); points after
// the peak are ignored.
ModulusFit fit_youngs_modulus(const std::vector<double>& strain, const std::vector<double>& stress,
                              double lower_fraction = 0.05, double window_fraction = 0.25);

// Per-type mean and standard deviation of sigma_xx, sigma_yy, sigma_zz over free particles.
std::vector<TypeStress> stress_by_type(const Packing& model, const std::vector<std::array<double, 9>>& stress);

// Histogram of the finite values: `bins` equal bins over [lo, hi]; returns counts.
std::vector<std::size_t> histogram(const std::vector<double>& values, double lo, double hi, int bins);

}  // namespace packlab::analyze
