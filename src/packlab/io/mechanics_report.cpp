#include "packlab/io/mechanics_report.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "packlab/analyze/stress_strain.hpp"
#ifdef PACKLAB_HAVE_PETSC
#include "packlab/mechanics/static_solver_petsc.hpp"
#endif

namespace packlab::io {

nlohmann::json oscillatory_shear_summary(const mechanics::OscillatoryShearResult& result) {
  nlohmann::json per = nlohmann::json::array();
  double plate_mean = 0.0;
  std::size_t broken = 0;
  double shear_ratio = 0.0, tension_ratio = 0.0, ke = 0.0;
  for (const auto& r : result.runs) {
    per.push_back({{"orientation", mechanics::orientation_name(r.orientation)},
                   {"plate_normal", std::string(1, "xyz"[r.orientation.normal])},
                   {"shear_direction", std::string(1, "xyz"[r.orientation.direction])},
                   {"storage_modulus", r.storage_modulus},
                   {"complex_modulus", r.complex_modulus},
                   {"phase_angle", r.phase_angle},
                   {"plate_storage_modulus", r.plate_storage_modulus},
                   {"broken_bonds", r.broken_bonds},
                   {"max_bond_shear_force", r.max_bond_shear_force},
                   {"max_bond_tension", r.max_bond_tension},
                   {"max_kinetic_to_strain_energy", r.max_kinetic_to_strain},
                   {"settle_steps", r.settle.steps},
                   {"structure_particles", r.structure_particles},
                   {"plate_particles", r.plate_particles},
                   {"bonds", r.bonds},
                   {"time_step", r.time_step},
                   {"steps", r.steps},
                   {"solver", r.solver},
                   {"solver_bytes", r.solver_bytes},
                   {"seconds", r.seconds}});
    plate_mean += r.plate_storage_modulus;
    broken += r.broken_bonds;
    shear_ratio = std::max(shear_ratio, r.max_bond_shear_ratio);
    tension_ratio = std::max(tension_ratio, r.max_bond_tension_ratio);
    ke = std::max(ke, r.max_kinetic_to_strain);
  }
  plate_mean /= static_cast<double>(std::max<std::size_t>(result.runs.size(), 1));
  nlohmann::json j;
  j["storage_modulus"] = {{"mean", result.storage_modulus_mean},
                          {"std", result.storage_modulus_std},
                          {"per_orientation", per},
                          {"unit", "Pa"}};
  j["phase_angle"] = result.phase_angle_mean;
  j["phase_angle_unit"] = "rad";
  j["phase_angle_over_pi"] = result.phase_angle_mean / std::numbers::pi;
  j["phase_angle_max_abs"] = result.phase_angle_max;
  j["plate_storage_modulus_mean"] = plate_mean;
  j["bonds"] = {{"broken_during_loading", broken},
                {"max_shear_force_over_strength", shear_ratio},
                {"max_tension_over_strength", tension_ratio}};
  j["max_kinetic_to_strain_energy"] = ke;
  const bool quasi_static = !result.runs.empty() && result.runs.front().solver == "static";
  j["solver"] = quasi_static ? "static" : "dynamic";
  if (quasi_static)
    j["solver_note"] =
        "static: one linear solve per orientation; no inertia or damping, so the phase angle is 0 by "
        "construction";
  if (result.relaxed)
    j["relaxation"] = {{"steps", result.relax.steps},
                       {"converged", result.relax.converged},
                       {"initial_mean_unbalanced_force", result.relax.initial_unbalanced_force},
                       {"final_mean_unbalanced_force", result.relax.final_unbalanced_force},
                       {"reason", result.relax.reason()}};
  j["seconds"] = result.seconds;
  j["particle_steps"] = result.particle_steps;
  j["particle_steps_per_second"] = result.seconds > 0.0 ? result.particle_steps / result.seconds : 0.0;
  return j;
}

nlohmann::json uniaxial_compression_summary(const mechanics::UniaxialCompressionResult& r,
                                            const mechanics::UniaxialCompressionOptions& o) {
  nlohmann::json j;
  j["solver"] = r.solver;
  j["youngs_modulus"] = r.youngs_modulus;
  j["strength"] = r.strength;
  j["broken_bonds"] = r.broken_bonds;
  j["strain_at_peak"] = r.strain_at_peak;
  j["modulus_fit"] = {{"method", "max_tangent"},
                      {"lower_fraction", o.modulus_lower},
                      {"window_fraction", o.modulus_window},
                      {"strain_begin", r.modulus.strain_begin},
                      {"strain_end", r.modulus.strain_end},
                      {"points", r.modulus.points},
                      {"r2", r.modulus.r2},
                      {"found", r.modulus.found}};
  j["height"] = r.height;
  j["area"] = r.area;
  j["plate_speed"] = r.plate_speed;
  j["strain_rate"] = o.strain_rate;
  if (r.solver == "dynamic" && o.elastic_speedup > 1.0)
    j["adaptive_rate"] = {{"elastic_speedup", o.elastic_speedup},
                          {"effective_speedup", r.effective_speedup},
                          {"switch_strain", std::isfinite(r.rate_switch_strain) ? nlohmann::json(r.rate_switch_strain)
                                                                                : nlohmann::json()},
                          {"rolled_back_steps", r.rolled_back_steps}};
  j["max_strain"] = o.max_strain;
  j["sides"] = o.sides;
  j["plate"] = o.plate;
  j["plate_layers"] = o.plate_layers;
  j["glued_particles"] = r.glued_particles;
  j["time_step"] = r.time_step;
  j["steps"] = r.steps;
  j["max_kinetic_to_strain_energy"] = r.max_kinetic_ratio;
  j["particles"] = r.particles;
  j["fixed_particles"] = r.fixed_particles;
  j["bonds"] = r.bonds;
  j["dropped_bonds"] = r.dropped_bonds;
  j["stop_reason"] = r.stop_reason;
  if (r.solver == "static") {
    j["static_solver"] = {
        {"backend", o.solver_backend},
        {"poisson_ratio", std::isfinite(r.poisson_ratio) ? nlohmann::json(r.poisson_ratio) : nlohmann::json()},
        {"solves", r.solves},
        {"factorizations", r.factorizations},
        {"downdates", r.downdates},
        {"checks", r.checks},
        {"check_interval", o.check_interval},
        {"rollbacks", r.rollbacks},
        {"pcg_iterations", r.pcg_iterations},
        {"factor_seconds", r.factor_seconds},
        {"downdate_seconds", r.downdate_seconds},
        {"check_seconds", r.check_seconds},
        {"solve_seconds", r.solve_seconds},
        {"matrix_and_factor_bytes", r.solver_bytes},
        {"strength_method", "sequential linear analysis (envelope of the bond breaks)"}};
#ifdef PACKLAB_HAVE_PETSC
    if (o.solver_backend == "petsc") j["static_solver"]["mpi_ranks"] = mechanics::petsc::ranks();
#endif
  }
  j["seconds"] = r.seconds;
  j["particle_steps_per_second"] =
      r.seconds > 0 ? static_cast<double>(r.particles) * static_cast<double>(r.steps) / r.seconds : 0.0;
  j["bond_steps_per_second"] =
      r.seconds > 0 ? static_cast<double>(r.bonds) * static_cast<double>(r.steps) / r.seconds : 0.0;
  nlohmann::json snaps = nlohmann::json::array();
  for (const auto& s : r.snapshots) {
    nlohmann::json sj{{"strain", s.strain}, {"stress", s.stress}};
    if (s.by_stress())
      sj["requested_stress"] = s.requested_stress;
    else
      sj["requested_strain"] = s.requested_strain;
    nlohmann::json types = nlohmann::json::array();
    for (const auto& t : analyze::stress_by_type(r.model, s.particle_stress))
      types.push_back({{"type", t.type},
                       {"particles", t.particles},
                       {"mean_xx", t.mean[0]},
                       {"mean_yy", t.mean[1]},
                       {"mean_zz", t.mean[2]},
                       {"sd_xx", t.sd[0]},
                       {"sd_yy", t.sd[1]},
                       {"sd_zz", t.sd[2]},
                       {"axial_to_vertical", t.mean[2] != 0.0 ? t.mean[0] / t.mean[2] : 0.0}});
    sj["stress_by_type"] = types;
    double lo = 0, hi = 0, sum = 0;
    std::size_t count = 0, compressed = 0;
    for (double e : s.bond_strain)
      if (std::isfinite(e)) {
        lo = std::min(lo, e);
        hi = std::max(hi, e);
        sum += e;
        ++count;
        compressed += e < 0.0;
      }
    sj["bond_strain"] = {
        {"min", lo},
        {"max", hi},
        {"mean", count ? sum / static_cast<double>(count) : 0.0},
        {"compressed_fraction", count ? static_cast<double>(compressed) / static_cast<double>(count) : 0.0}};
    snaps.push_back(sj);
  }
  j["snapshots"] = snaps;
  j["units"] = {{"youngs_modulus", "Pa"}, {"strength", "Pa"},     {"height", "m"},    {"area", "m^2"},
                {"plate_speed", "m/s"},   {"strain_rate", "1/s"}, {"time_step", "s"}, {"stress", "Pa"}};
  return j;
}

nlohmann::json compression_calibration_summary(const mechanics::CompressionCalibrationResult& result,
                                               const mechanics::CalibrationOptions& options) {
  const mechanics::CalibrationResult& c = result.calibration;
  nlohmann::json history = nlohmann::json::array();
  int evaluation = 0;
  for (const auto& h : c.history)
    history.push_back({{"evaluation", ++evaluation},
                       {"bond_youngs_modulus", h.parameters[0]},
                       {"bond_strength", h.parameters[1]},
                       {"youngs_modulus", h.responses[0]},
                       {"strength", h.responses[1]},
                       {"finite_difference", h.finite_difference}});
  return {
      {"mode", "calibrate"},
      {"scheme", options.diagonal ? "diagonal (paper: dE/dsigma = dS/dE_b = 0)" : "full finite-difference Jacobian"},
      {"converged", c.converged},
      {"reason", c.reason()},
      {"iterations", c.iterations},
      {"simulations", c.evaluations},
      {"bond_youngs_modulus", c.parameters[0]},
      {"bond_strength", c.parameters[1]},
      {"youngs_modulus", c.responses[0]},
      {"strength", c.responses[1]},
      {"history", history}};
}

nlohmann::json bulk_factor_summary(const mechanics::BulkFactorResult& b, const mechanics::UniaxialCompressionSetup& s) {
  return {{"mode", "bulk_factor"},
          {"bond_youngs_modulus", s.materials.silica_youngs_modulus},
          {"bond_strength", s.materials.silica_strength},
          {"bulk_factor", b.bulk_factor},
          {"strength_ratio", b.strength_ratio},
          {"strength_factor", b.strength_factor},
          {"youngs_modulus", b.run.youngs_modulus},
          {"strength", b.run.strength},
          {"compression", uniaxial_compression_summary(b.run, s.options)}};
}

}  // namespace packlab::io
