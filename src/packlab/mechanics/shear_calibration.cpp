#include "packlab/mechanics/shear_calibration.hpp"

#include <cmath>

#include "packlab/core/error.hpp"
#include "packlab/mechanics/calibration.hpp"

namespace packlab::mechanics {

ShearCalibrationResult calibrate_normal_stiffness(const Packing& bonded, double target,
                                                  const OscillatoryShearOptions& options, double tolerance,
                                                  int max_iterations, CalibrationProgress* progress) {
  validate(options);
  require(target > 0.0 && std::isfinite(target), "target storage modulus", target, "> 0 Pa");
  OscillatoryShearOptions o = options;
  // The §2.2 relaxation does not depend on k_n (a step moves x by F/m dt^2 and dt^2 ~ m/k), so
  // relax once and shear the same structure at every k_n.
  const Packing relaxed = o.relax ? relax_bonded(bonded, o) : bonded;
  const double ratio = options.shear_stiffness / options.normal_stiffness;
  ShearCalibrationResult out;
  auto response = [&](const std::vector<double>& p) {
    OscillatoryShearOptions e = o;
    e.normal_stiffness = p[0];
    e.shear_stiffness = ratio * p[0];
    e.relax = false;
    if (progress != nullptr) progress->attach(p, e.resume, e.checkpoint);
    OscillatoryShearResult r = run_oscillatory_shear(relaxed, e);
    return std::vector<double>{r.storage_modulus_mean};
  };
  CalibrationOptions co;
  co.tolerance = tolerance;
  co.max_iterations = max_iterations;
  const CalibrationResult c = calibrate(response, {options.normal_stiffness}, {target}, co, progress);
  // The evaluations replayed from a checkpoint are in the history, not in the calls above.
  out.tried_normal_stiffness.clear();
  out.tried_storage_modulus.clear();
  for (const CalibrationStep& step : c.history) {
    out.tried_normal_stiffness.push_back(step.parameters[0]);
    out.tried_storage_modulus.push_back(step.responses[0]);
  }
  out.normal_stiffness = c.parameters[0];
  out.shear_stiffness = ratio * c.parameters[0];
  out.storage_modulus = c.responses[0];
  out.converged = c.converged;
  out.iterations = c.iterations;
  out.evaluations = c.evaluations;
  out.reason = c.reason();
  return out;
}

}  // namespace packlab::mechanics
