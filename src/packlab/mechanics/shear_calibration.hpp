// Calibration of the particle normal stiffness by the oscillatory shear test
// (doh-elastic-properties §2.4), behind `packlab calibrate shear` and packlab.calibrate_shear.
#pragma once

#include <string>
#include <vector>

#include "packlab/core/packing.hpp"
#include "packlab/mechanics/calibration.hpp"
#include "packlab/mechanics/oscillatory_shear.hpp"

namespace packlab::mechanics {

// Calibration: k_n such that the mean G' over `options.orientations` equals
// target [Pa], k_s following at the ratio k_s/k_n of the options; Newton with a
// finite-difference derivative (mechanics::calibrate). G' is linear in k_n at a fixed ratio,
// so one Newton step lands on the target.
struct ShearCalibrationResult {
  double normal_stiffness = 0.0;  // [N/m]
  double shear_stiffness = 0.0;   // [N/m]
  double storage_modulus = 0.0;   // at the result [Pa]
  bool converged = false;
  int iterations = 0, evaluations = 0;
  std::vector<double> tried_normal_stiffness, tried_storage_modulus;
  std::string reason;
};
// `progress` (optional) makes the run resumable (mechanics/calibration.hpp); the relaxation
// before the first evaluation is done again on resume (it is deterministic).
ShearCalibrationResult calibrate_normal_stiffness(const Packing& bonded, double target,
                                                  const OscillatoryShearOptions& options, double tolerance = 0.005,
                                                  int max_iterations = 10, CalibrationProgress* progress = nullptr);

}  // namespace packlab::mechanics
