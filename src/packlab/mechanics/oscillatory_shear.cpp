// Oscillatory shear: the loading protocol of one orientation and of the whole test. Set-up:
// oscillatory_shear_setup.cpp; per-cycle evaluation: oscillatory_shear_evaluation.cpp.
#include "packlab/mechanics/oscillatory_shear.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "packlab/core/error.hpp"
#include "packlab/dem/material.hpp"
#include "packlab/mechanics/static_loading.hpp"

namespace packlab::mechanics {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

namespace {

void require_periodic_bonded(const Packing& p) {
  p.validate();
  if (!(p.box.periodic[0] && p.box.periodic[1] && p.box.periodic[2]))
    fail_input(
        "test shear: the packing's box must be periodic along x, y and z (the plates are its periodic "
        "images)");
  bool intact = false;
  for (int s : p.bonds.state) intact = intact || s == 0;
  if (!intact)
    fail_input(
        "test shear: the packing has no intact bond; make a bonded model first (packlab bond IN "
        "--model contact --out FILE.vtu)");
}

}  // namespace

ShearRun run_shear_orientation(const Packing& bonded, const ShearOrientation& orientation,
                               const OscillatoryShearOptions& options) {
  if (options.solver == "static") return run_static_shear_orientation(bonded, orientation, options);
  validate(options);
  require_periodic_bonded(bonded);
  const auto t0 = std::chrono::steady_clock::now();
  ShearRun run;
  run.orientation = orientation;
  const std::string stage = orientation_name(orientation);
  ShearSetup setup = build_shear_setup(oriented_packing(bonded, orientation), options.plate_layers, options.regions);
  run.structure_particles = setup.structure;
  run.plate_particles = setup.lower + setup.upper;
  run.bonds = setup.packing.bonds.size();
  dem::Engine engine(setup.packing, shear_engine_config(options));
  run.time_step = engine.time_step();
  const std::size_t bonds_before = engine.intact_bonds();

  // Settle the set-up (plates fixed): the bond shear histories of the §2.2 relaxation are not
  // carried over, so balance the forces again with the same procedure.
  if (options.settle) {
    dem::ZeroVelocityRelaxOptions ro = options.relax_options;
    run.settle = dem::relax_zeroing_velocities(engine, ro);
    run.steps += run.settle.steps;
  }

  // Internal indices of the upper plate.
  std::vector<std::size_t> upper;
  for (std::size_t k = 0; k < engine.particle_count(); ++k)
    if (setup.role[static_cast<std::size_t>(engine.original_index()[k])] == 2) upper.push_back(k);

  const double H = setup.height;
  const double dt = engine.time_step();
  const long S = options.steps_per_cycle;
  const long interval = S / options.samples_per_cycle;
  const long total = S * options.cycles;
  double deflection = 0.0;
  double max_kinetic = 0.0, max_strain_energy = 0.0;
  auto& P = engine.particles();

  auto sample = [&](int cycle, long step, double phase, const dem::Diagnostics& d) {
    ShearSample x;
    x.cycle = cycle;
    x.step = step;
    x.time = static_cast<double>(step) * dt;
    x.phase = phase;
    x.strain = deflection / H;
    x.kinetic_energy = d.kinetic_energy;
    x.strain_energy = d.strain_energy;
    ShearStress st = shear_stress(engine.contact_forces(), setup, options.regions);
    run.max_bond_tension = std::max(run.max_bond_tension, st.max_bond_tension);
    run.max_bond_shear_force = std::max(run.max_bond_shear_force, st.max_bond_shear_force);
    x.region_stress = std::move(st.region_stress);
    x.stress = st.stress;
    x.plate_stress = st.plate_stress;
    max_kinetic = std::max(max_kinetic, d.kinetic_energy);
    max_strain_energy = std::max(max_strain_energy, d.strain_energy);
    run.samples.push_back(std::move(x));
  };

  long done = 0;
  for (int cycle = 1; cycle <= options.cycles; ++cycle) {
    const double A = options.amplitude * H * cycle / options.cycles;
    for (long s = 0; s < S; ++s) {
      const double u0 = A * std::sin(2.0 * std::numbers::pi * static_cast<double>(s) / static_cast<double>(S));
      const double u1 = A * std::sin(2.0 * std::numbers::pi * static_cast<double>(s + 1) / static_cast<double>(S));
      const double v = (u1 - u0) / dt;
      for (std::size_t k : upper) P.velocity[k] = Vec3{v, 0.0, 0.0};
      const bool measure = (s + 1) % interval == 0;
      if (measure) {
        const dem::Diagnostics d = engine.step_measured();
        deflection += v * dt;
        ++done;
        sample(cycle, done, 2.0 * std::numbers::pi * static_cast<double>(s + 1) / static_cast<double>(S), d);
        if (options.progress) options.progress(stage, done, total);
      } else {
        engine.run(1);
        deflection += v * dt;
        ++done;
      }
    }
  }
  for (std::size_t k : upper) P.velocity[k] = Vec3{};
  run.steps += done;
  run.broken_bonds = bonds_before - engine.intact_bonds();
  for (int cycle = 1; cycle <= options.cycles; ++cycle) run.cycles.push_back(evaluate_cycle(run.samples, cycle));
  for (const auto& c : run.cycles) {
    run.storage_modulus += c.storage_modulus;
    run.complex_modulus += c.complex_modulus;
    run.phase_angle += c.phase_angle;
    run.plate_storage_modulus += c.plate_storage_modulus;
  }
  const double nc = static_cast<double>(run.cycles.size());
  run.storage_modulus /= nc;
  run.complex_modulus /= nc;
  run.phase_angle /= nc;
  run.plate_storage_modulus /= nc;
  run.max_kinetic_to_strain = max_strain_energy > 0.0 ? max_kinetic / max_strain_energy : 0.0;
  run.max_bond_tension_ratio = run.max_bond_tension / options.normal_strength;
  run.max_bond_shear_ratio = run.max_bond_shear_force / options.shear_strength;
  run.seconds = seconds_since(t0);
  return run;
}

OscillatoryShearResult run_oscillatory_shear(const Packing& bonded, const OscillatoryShearOptions& options) {
  validate(options);
  require_periodic_bonded(bonded);
  const auto t0 = std::chrono::steady_clock::now();
  OscillatoryShearResult result;
  const auto save = [&](std::ostream& out) { save_shear_progress(out, result); };
  const bool checkpoints = options.checkpoint && options.solver != "static";
  const std::vector<ShearOrientation> orientations = shear_orientations(options.orientations);
  if (options.resume != nullptr && options.solver != "static") {
    load_shear_progress(*options.resume, result);
    if (result.runs.size() > orientations.size())
      fail_input("checkpoint is damaged: more orientations than the test runs");
  } else {
    if (options.relax) {
      result.relaxed_packing = relax_bonded(bonded, options, &result.relax);
      result.relaxed = true;
      result.particle_steps += static_cast<double>(bonded.size()) * static_cast<double>(result.relax.steps);
    } else {
      result.relaxed_packing = bonded;
    }
    if (checkpoints) options.checkpoint(save, false);
  }
  for (std::size_t k = result.runs.size(); k < orientations.size(); ++k) {
    result.runs.push_back(run_shear_orientation(result.relaxed_packing, orientations[k], options));
    const ShearRun& r = result.runs.back();
    result.particle_steps +=
        static_cast<double>(r.structure_particles + r.plate_particles) * static_cast<double>(r.steps);
    if (checkpoints) options.checkpoint(save, false);
  }
  if (checkpoints) options.checkpoint(save, true);
  double sum = 0.0;
  for (const auto& r : result.runs) {
    sum += r.storage_modulus;
    result.phase_angle_mean += r.phase_angle;
    for (const auto& c : r.cycles) result.phase_angle_max = std::max(result.phase_angle_max, std::abs(c.phase_angle));
  }
  const double n = static_cast<double>(result.runs.size());
  result.storage_modulus_mean = sum / n;
  result.phase_angle_mean /= n;
  double var = 0.0;
  for (const auto& r : result.runs)
    var += (r.storage_modulus - result.storage_modulus_mean) * (r.storage_modulus - result.storage_modulus_mean);
  result.storage_modulus_std = result.runs.size() > 1 ? std::sqrt(var / (n - 1.0)) : 0.0;
  result.seconds = seconds_since(t0);
  return result;
}

}  // namespace packlab::mechanics
