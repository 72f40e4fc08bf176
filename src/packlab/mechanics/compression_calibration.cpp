#include "packlab/mechanics/compression_calibration.hpp"

#include <utility>

#include "packlab/core/error.hpp"

namespace packlab::mechanics {

CompressionCalibrationResult calibrate_compression(const Packing& model, const UniaxialCompressionSetup& setup,
                                                   double target_youngs_modulus, double target_strength,
                                                   const CalibrationOptions& options,
                                                   const CompressionRunCallback& on_run) {
  require(target_youngs_modulus > 0.0, "target_youngs_modulus", target_youngs_modulus,
          "> 0 Pa (or compute the bulk factor)");
  require(target_strength > 0.0, "target_strength", target_strength, "> 0 Pa");
  std::vector<std::pair<std::vector<double>, UniaxialCompressionResult>> runs;
  auto response = [&](const std::vector<double>& p) {
    UniaxialCompressionSetup run = setup;
    run.materials.silica_youngs_modulus = p[0];
    run.materials.silica_strength = p[1];
    run.options.types = opal_particle_types(run.materials);
    run.options.bond_materials = opal_bond_materials(run.materials);
    UniaxialCompressionResult r = run_uniaxial_compression(model, run.options);
    if (on_run) on_run(static_cast<int>(runs.size()) + 1, p, r);
    std::vector<double> out{r.youngs_modulus, r.strength};
    runs.emplace_back(p, std::move(r));
    return out;
  };
  CompressionCalibrationResult result;
  result.calibration = calibrate(response, {setup.materials.silica_youngs_modulus, setup.materials.silica_strength},
                                 {target_youngs_modulus, target_strength}, options);
  for (auto it = runs.rbegin(); it != runs.rend(); ++it)
    if (it->first == result.calibration.parameters) {
      result.final = std::move(it->second);
      result.has_final = true;
      break;
    }
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
