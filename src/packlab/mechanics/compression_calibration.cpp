#include "packlab/mechanics/compression_calibration.hpp"

#include <utility>

#include "packlab/core/error.hpp"

namespace packlab::mechanics {

CompressionCalibrationResult calibrate_compression(const Packing& model, const UniaxialCompressionSetup& setup,
                                                   double target_youngs_modulus, double target_strength,
                                                   const CalibrationOptions& options,
                                                   const CompressionRunCallback& on_run,
                                                   CalibrationProgress* progress) {
  require(target_youngs_modulus > 0.0, "target_youngs_modulus", target_youngs_modulus,
          "> 0 Pa (or compute the bulk factor)");
  require(target_strength > 0.0, "target_strength", target_strength, "> 0 Pa");
  // The calibration ends on an iterate (never on a finite-difference run): keep the last run.
  std::vector<double> last_parameters;
  UniaxialCompressionResult last;
  int simulation = progress != nullptr ? static_cast<int>(progress->done.size()) : 0;
  auto simulate = [&](const std::vector<double>& p) {
    UniaxialCompressionSetup run = setup;
    run.materials.silica_youngs_modulus = p[0];
    run.materials.silica_strength = p[1];
    run.options.types = opal_particle_types(run.materials);
    run.options.bond_materials = opal_bond_materials(run.materials);
    if (progress != nullptr) progress->attach(p, run.options.resume, run.options.checkpoint);
    return run_uniaxial_compression(model, run.options);
  };
  auto response = [&](const std::vector<double>& p) {
    UniaxialCompressionResult r = simulate(p);
    if (on_run) on_run(++simulation, p, r);
    std::vector<double> out{r.youngs_modulus, r.strength};
    last_parameters = p;
    last = std::move(r);
    return out;
  };
  CompressionCalibrationResult result;
  result.calibration = calibrate(response, {setup.materials.silica_youngs_modulus, setup.materials.silica_strength},
                                 {target_youngs_modulus, target_strength}, options, progress);
  if (last_parameters != result.calibration.parameters) {
    // A resumed run whose last simulation was replayed from its checkpoint: the outputs of the
    // final parameters need that simulation once more (it gives the same result).
    last = simulate(result.calibration.parameters);
    last_parameters = result.calibration.parameters;
  }
  result.final = std::move(last);
  result.has_final = true;
  return result;
}

Columns calibration_history_columns(const CalibrationResult& c) {
  std::vector<double> evaluation, fd, e_b, sigma, e, strength;
  for (std::size_t k = 0; k < c.history.size(); ++k) {
    const CalibrationStep& h = c.history[k];
    evaluation.push_back(static_cast<double>(k));
    fd.push_back(h.finite_difference ? 1.0 : 0.0);
    e_b.push_back(h.parameters[0]);
    sigma.push_back(h.parameters[1]);
    e.push_back(h.responses[0]);
    strength.push_back(h.responses[1]);
  }
  Columns t;
  t.add("evaluation", std::move(evaluation), Column::Kind::integer);
  t.add("finite_difference", std::move(fd), Column::Kind::flag);
  t.add("bond_youngs_modulus", std::move(e_b));
  t.add("bond_strength", std::move(sigma));
  t.add("youngs_modulus", std::move(e));
  t.add("strength", std::move(strength));
  return t;
}

BulkFactorResult compression_bulk_factor(const Packing& model, const UniaxialCompressionSetup& setup) {
  BulkFactorResult b;
  b.run = run_uniaxial_compression(model, setup.options);
  const UniaxialCompressionResult& r = b.run;
  b.bulk_factor = r.youngs_modulus / setup.materials.silica_youngs_modulus;
  b.strength_ratio = r.strength > 0 ? r.youngs_modulus / r.strength : 0.0;
  b.strength_factor = r.strength / setup.materials.silica_strength;
  return b;
}

}  // namespace packlab::mechanics
