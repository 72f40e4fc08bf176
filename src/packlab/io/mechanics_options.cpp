// The option sets of the mechanical tests (io/options.hpp): oscillatory shear, uniaxial
// compression and their calibrations.
#include <fmt/format.h>

#include "packlab/core/error.hpp"
#include "packlab/io/adapt_threads_help.hpp"
#include "packlab/io/options.hpp"

namespace packlab::io {

void add_oscillatory_shear_options(ConfigSchema& schema, mechanics::OscillatoryShearOptions& t) {
  schema.number("normal_stiffness", t.normal_stiffness, "Particle normal stiffness k_n")
      .unit("N/m")
      .range(ranges::positive)
      .number("shear_stiffness", t.shear_stiffness, "Particle shear stiffness k_s")
      .unit("N/m")
      .range(ranges::non_negative)
      .number("normal_strength", t.normal_strength, "Bond normal strength F_nB")
      .unit("N")
      .range(ranges::positive_or_inf)
      .number("shear_strength", t.shear_strength, "Bond shear strength F_sB")
      .unit("N")
      .range(ranges::positive_or_inf)
      .number("friction", t.friction, "Friction coefficient mu of unbonded contacts")
      .range(ranges::non_negative)
      .number("damping", t.damping, "Local damping coefficient alpha")
      .range({0.0, 1.0, false, true})
      .number("density", t.density, "Particle density (when the file has none)")
      .unit("kg/m^3")
      .range(ranges::positive)
      .text("stiffness_rule", t.stiffness_rule,
            "particle: k are PFC particle stiffnesses, contacts and bonds act with k/2; contact: k act as given")
      .integer("cycles", t.cycles, "Oscillation cycles (amplitude rising linearly to `amplitude`)")
      .range({1.0, 1000.0, false, false})
      .number("amplitude", t.amplitude, "Largest plate deflection / box edge")
      .range({0.0, 0.1, true, false})
      .integer("steps_per_cycle", t.steps_per_cycle,
               "Steps per cycle (the quasi-static loading rate); a multiple of samples_per_cycle")
      .range({8.0, 1e12, false, false})
      .integer("samples_per_cycle", t.samples_per_cycle, "Stress samples per cycle (a multiple of 4)")
      .range({8.0, 1e6, false, false})
      .integer("plate_layers", t.plate_layers, "Particle layers of each plate")
      .range({1.0, 10.0, false, false})
      .integer("regions", t.regions, "Measurement slabs at heights H (k+1)/(regions+1)")
      .range({1.0, 50.0, false, false})
      .text("orientations", t.orientations,
            "all, plate normals (x,y,z: both shear directions each) or "
            "normal:direction pairs (z:x,...)")
      .number("time_step_safety", t.time_step_safety, "Time step as a fraction of sqrt(m/k)")
      .range({0.0, 1.0, true, false})
      .integer("threads", t.threads, "OpenMP threads (0 = all cores)")
      .range({0.0, 1024.0, false, false})
      .boolean("adapt_threads", t.adapt_threads, adapt_threads_help("Dynamic solver, more than one thread"))
      .text("solver", t.solver,
            "dynamic: oscillating plate in explicit DEM; static: one quasi-static linear solve per orientation "
            "(phase angle 0 by construction; docs/static-solver.md)")
      .text("solver_backend", t.solver_backend,
            "Static solver's sparse Cholesky: auto, cholmod, eigen or petsc (MPI; in a build with PETSc)")
      .text("petsc_options", t.petsc_options,
            "Static solver, petsc backend: PETSc options, e.g. \"-ksp_type cg -pc_type gamg\" (default: Cholesky by "
            "MUMPS)")
      .boolean("relax.enabled", t.relax,
               "Relax the periodic bonded structure first (§2.2: velocities zeroed after "
               "each step)")
      .alias("relax")
      .boolean("relax.settle", t.settle, "Settle the test set-up (plates fixed) with the same procedure before loading")
      .alias("settle")
      .integer("relax.max_steps", t.relax_options.max_steps, "Step limit of the relaxation and of the settling")
      .range({1.0, ranges::inf, false, true})
      .integer("relax.check_interval", t.relax_options.check_interval, "Steps between two checks")
      .range({1.0, ranges::inf, false, true})
      .number("relax.min_decrease", t.relax_options.min_decrease,
              "Relative decrease of the mean unbalanced force that counts as progress")
      .range({0.0, 1.0, true, true})
      .integer("relax.patience", t.relax_options.patience, "Checks without progress that end the relaxation")
      .range({1.0, ranges::inf, false, true});
}

ConfigSchema shear_test_options(ShearTestRun& r) {
  ConfigSchema schema("test shear", "The oscillatory shear test (docs/shear.md).", "shear_test");
  add_oscillatory_shear_options(schema, r.test);
  schema.boolean("output.plots", r.plots, "Draw the PNG plots").command_only();
  add_checkpoint_seconds(schema, r.checkpoint_seconds);
  return schema;
}

ConfigSchema shear_calibration_options(ShearCalibrationRun& r) {
  ConfigSchema schema("calibrate shear",
                      "Calibration of k_n to a target storage modulus by the oscillatory shear test (docs/shear.md).",
                      "calibrate_shear");
  schema.number("target_storage_modulus", r.target_storage_modulus, "Target mean storage modulus G'")
      .unit("Pa")
      .range(ranges::positive)
      .number("tolerance", r.tolerance, "Relative tolerance on G'")
      .range({0.0, 1.0, true, true})
      .integer("max_iterations", r.max_iterations, "Newton iterations at most")
      .range({1.0, 1000.0, false, false});
  add_oscillatory_shear_options(schema, r.test);
  add_checkpoint_seconds(schema, r.checkpoint_seconds);
  return schema;
}

void add_uniaxial_compression_options(ConfigSchema& schema, mechanics::UniaxialCompressionOptions& o) {
  schema.number("max_strain", o.max_strain, "Largest strain")
      .range({0.0, 0.5, true, true})
      .number("elastic_speedup", o.elastic_speedup,
              "Dynamic solver: the plate moves this many times faster until the first bond breaks, then the run "
              "goes back to the curve point before that break, slows the sample down with the plate and goes on at "
              "strain_rate (1 = strain_rate throughout; docs/opal.md)")
      .range({1.0, 1e4, false, false})
      .number("stop_drop", o.stop_drop,
              "Stop past the peak once the stress is below this fraction of it (static solver: also once it "
              "cannot come back above it before max_strain; 0 = run to max_strain)")
      .range({0.0, 1.0, false, true})
      .text("sides", o.sides, "periodic: keep the model's periodic x, y; open: free-standing pillar")
      .text("plate", o.plate,
            "glued: the top plate_layers move with the plate (no contact toe); contact: a Hertz-Mindlin plate "
            "touching the top (the paper's; rough tops give a toe of about r / H0)")
      .number("plate_layers", o.plate_layers, "Glued plate: top layers moving with it (mean diameters)")
      .range({0.0, 100.0, true, false})
      .number("substrate_layers", o.substrate_layers,
              "Bottom layers fixed when the model has no fixed particles (mean diameters)")
      .range({0.0, 100.0, false, false})
      .number("time_step", o.time_step, "Time step; 0 = safety x min sqrt(m/k)")
      .unit("s")
      .range(ranges::non_negative)
      .number("time_step_safety", o.time_step_safety, "Safety factor of the automatic time step")
      .range({0.0, 1.0, true, false})
      .integer("samples", o.samples, "Curve points over max_strain")
      .range({10.0, 1e7, false, false})
      .number("modulus_lower", o.modulus_lower,
              "Young's modulus fit: ignore points below this fraction of the peak stress")
      .range({0.0, 1.0, false, true})
      .number("modulus_window", o.modulus_window, "Young's modulus fit: window width as a fraction of the peak stress")
      .range({0.0, 1.0, true, false})
      .integer("threads", o.threads, "OpenMP threads (0 = all cores)")
      .range({0.0, 1024.0, false, false})
      .boolean("adapt_threads", o.adapt_threads, adapt_threads_help("Dynamic solver, more than one thread"))
      .text("solver", o.solver,
            "dynamic: explicit DEM at strain_rate; static: quasi-static linear solves, strength by sequential "
            "linear analysis (docs/static-solver.md)")
      .text("solver_backend", o.solver_backend,
            "Static solver's sparse Cholesky: auto, cholmod, eigen or petsc (MPI; in a build with PETSc)")
      .text("petsc_options", o.petsc_options,
            "Static solver, petsc backend: PETSc options, e.g. \"-ksp_type cg -pc_type gamg\" (default: Cholesky by "
            "MUMPS)")
      .integer("max_breaks", o.max_breaks, "Static solver: stop after this many bond breaks (0 = no limit)")
      .range({0.0, 1e12, false, false})
      .integer("check_interval", o.check_interval,
               "Static solver: check every n-th re-solve after a bond break against the matrix (1 = each); a failed "
               "check goes back to the last checked break (docs/static-solver.md)")
      .range({1.0, 1e6, false, false})
      .integer("checkpoint_breaks", o.checkpoint_breaks,
               "Static solver: factorize anew after every this many bond breaks, where a checkpoint is written "
               "once checkpoint_seconds have passed (a resumed run gives the uninterrupted run's results)")
      .range({1.0, 1e12, false, false});
}

namespace {

void add_opal_materials(ConfigSchema& schema, mechanics::OpalMaterials& m) {
  schema
      .number("silica.youngs_modulus", m.silica_youngs_modulus,
              "Silica bond and particle Young's modulus E_b (bond material 0; every bond of a one-material model)")
      .unit("Pa")
      .range(ranges::positive)
      .alias("bond_youngs_modulus")
      .number("silica.poisson_ratio", m.silica_poisson_ratio, "Silica bond Poisson ratio nu_b")
      .range({-1.0, 0.5, true, false})
      .alias("bond_poisson_ratio")
      .number("silica.strength", m.silica_strength, "Silica bond strength sigma_max = tau_max (eq. 16-17)")
      .unit("Pa")
      .range(ranges::positive_or_inf)
      .alias("bond_strength")
      .number("silica.density", m.silica_density, "Silica particle density")
      .unit("kg/m^3")
      .range(ranges::positive)
      .alias("density")
      .number("titania.youngs_modulus", m.titania_youngs_modulus,
              "Titania (coating) bond Young's modulus (bond "
              "material 1)")
      .unit("Pa")
      .range(ranges::positive)
      .number("titania.poisson_ratio", m.titania_poisson_ratio, "Titania bond Poisson ratio")
      .range({-1.0, 0.5, true, false})
      .number("titania.strength", m.titania_strength, "Titania bond strength")
      .unit("Pa")
      .range(ranges::positive_or_inf)
      .number("titania.density", m.titania_density, "Titania particle density")
      .unit("kg/m^3")
      .range(ranges::positive)
      .number("restitution", m.restitution, "Restitution coefficient of unbonded contacts and the plate")
      .range({0.0, 1.0, true, false})
      .number("friction", m.friction, "Sliding friction mu_sl")
      .range(ranges::non_negative)
      .number("rolling_friction", m.rolling_friction, "Rolling friction mu_r")
      .range(ranges::non_negative)
      .number("damping", m.damping, "Local (Cundall) damping alpha for the quasi-static run")
      .range({0.0, 1.0, false, true})
      .number("bond.radius_ratio", m.bond_radius_ratio, "Bond radius / smaller particle radius")
      .range({0.0, 1.0, true, false})
      .number("bond.relaxation_time", m.relaxation_time,
              "Time a failed bond stays while its stiffness decays linearly to zero")
      .unit("s")
      .range(ranges::non_negative)
      .boolean(
          "bond.compressive_breakage", m.compressive_breakage,
          "Apply the normal-stress criterion (eq. 16) to compressed bonds too (default: stretched only, as MUSEN)");
}

}  // namespace

namespace {

// The keys of the test, shared with its calibration.
void add_compression_test_keys(ConfigSchema& schema, mechanics::UniaxialCompressionSetup& s) {
  add_opal_materials(schema, s.materials);
  schema
      .number("strain_rate", s.strain_rate,
              "Plate speed / sample height; 0 = automatic: quasi_static strain per elastic-wave transit")
      .unit("1/s")
      .range(ranges::non_negative)
      .number("quasi_static", s.quasi_static,
              "Automatic rate: strain per time sqrt(rho/E_b) H0 (smaller = slower, closer to quasi-static)")
      .range({0.0, 0.1, true, false})
      .numbers("snapshot_strains", s.snapshot_strains,
               "Strains at which bond strains and particle stresses are recorded (Fig. 7, Table 2), each in "
               "(0, max_strain]")
      .numbers("snapshot_stresses", s.snapshot_stresses,
               "Applied stresses at which the same snapshots are recorded, each where the stress first reaches "
               "it (Table 2: 31.3e6); a stress never reached gives none")
      .unit("Pa")
      .range(ranges::positive);
  add_uniaxial_compression_options(schema, s.options);
}

}  // namespace

ConfigSchema compression_test_options(mechanics::UniaxialCompressionSetup& s) {
  ConfigSchema schema("test compress", "Uniaxial compression of a bonded model (docs/opal.md).", "compression_test");
  add_compression_test_keys(schema, s);
  add_checkpoint_seconds(schema, s.checkpoint_seconds);
  return schema;
}

ConfigSchema compression_calibration_options(CompressionCalibrationRun& r) {
  ConfigSchema schema(
      "calibrate compress",
      "Calibration of the silica bond to a target Young's modulus and strength (eq. 18-19), or the bulk "
      "factor K_E (eq. 20) (docs/opal.md).",
      "calibrate_compress");
  schema.number("target_youngs_modulus", r.target_youngs_modulus, "Target Young's modulus E* of the sample")
      .unit("Pa")
      .range(ranges::non_negative)
      .number("target_strength", r.target_strength, "Target compressive strength of the sample")
      .unit("Pa")
      .range(ranges::non_negative)
      .boolean("bulk_factor", r.bulk_factor,
               "Pore-free sample: report K_E = E_macro / E_b and E_macro / strength instead of calibrating")
      .number("tolerance", r.calibration.tolerance, "Relative tolerance per response")
      .range({0.0, 1.0, true, true})
      .integer("max_iterations", r.calibration.max_iterations, "Newton iterations at most")
      .range({1.0, 1000.0, false, false})
      .number("relative_step", r.calibration.relative_step, "Finite-difference step / parameter (eq. 19)")
      .range({0.0, 1.0, true, true})
      .boolean("full_jacobian", r.full_jacobian,
               "Use every finite-difference derivative (default: E from E_b and strength from sigma_max only, as the "
               "paper)");
  add_compression_test_keys(schema, r.setup);
  add_checkpoint_seconds(schema, r.setup.checkpoint_seconds);
  return schema;
}

}  // namespace packlab::io
