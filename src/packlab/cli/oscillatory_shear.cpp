// packlab test shear IN [--config FILE] [--normal-stiffness 100 --shear-stiffness 10 --cycles 10
//   --amplitude 0.001 --orientations all|x,y,z|z:x,... --relax-max-steps N] --out DIR
// The oscillatory shear test of doh-elastic-properties §2.4 on a bonded model (any file with
// bonds: `packlab bond` output, lattices included): §2.2 relaxation, plates from the periodic
// repetition, ten cycles of linearly increasing amplitude, G' = |G*| cos(delta) per orientation.
// Writes DIR/stress_strain.csv (every sample), DIR/cycles.csv (per cycle and orientation),
// DIR/shear.png (Fig. 4), DIR/relaxed.vtu (the tested structure with its bonds) and
// DIR/report.json.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>

#include "packlab/cli/commands.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/progress.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/config.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/plot.hpp"
#include "packlab/io/report.hpp"
#include "packlab/io/table.hpp"
#include "packlab/mechanics/oscillatory_shear.hpp"

namespace packlab::cli {

// Shared with calibrate_shear.cpp (declared there): the material/loading flags and config keys of
// both shear commands, and the report's parameter block.
std::function<void(mechanics::OscillatoryShearOptions&, std::string&, bool&)> add_shear_flags(CLI::App* cmd,
                                                                                       const std::string& command);
nlohmann::json shear_parameters_json(const mechanics::OscillatoryShearOptions& t, const std::string& orientations);

namespace {

struct ShearCliOptions {
  mechanics::OscillatoryShearOptions test;
  std::string orientations = "all";
  std::string config;
  bool no_relax = false;
  bool plots = true;
};

}  // namespace

namespace {

io::ConfigSchema shear_config_schema(const std::string& command, ShearCliOptions& o) {
  io::ConfigSchema s(command, "The oscillatory shear test (docs/shear.md); flags override the file.");
  auto& t = o.test;
  s.number("normal_stiffness", t.normal_stiffness, "Particle normal stiffness k_n [N/m]")
      .number("shear_stiffness", t.shear_stiffness, "Particle shear stiffness k_s [N/m]")
      .number("normal_strength", t.normal_strength, "Bond normal strength F_nB [N]")
      .number("shear_strength", t.shear_strength, "Bond shear strength F_sB [N]")
      .number("friction", t.friction, "Friction coefficient mu of unbonded contacts [-]")
      .number("damping", t.damping, "Local damping coefficient alpha, in [0, 1)")
      .number("density", t.density, "Particle density [kg/m^3] (when the file has none)")
      .text("stiffness_rule", t.stiffness_rule,
            "particle: k are PFC particle stiffnesses, contacts and bonds act with k/2; contact: k act as given")
      .integer("cycles", t.cycles, "Oscillation cycles (amplitude rising linearly to `amplitude`)")
      .number("amplitude", t.amplitude, "Largest plate deflection / box edge [-]")
      .integer("steps_per_cycle", t.steps_per_cycle, "Steps per cycle (the quasi-static loading rate)")
      .integer("samples_per_cycle", t.samples_per_cycle, "Stress samples per cycle (multiple of 4)")
      .integer("plate_layers", t.plate_layers, "Particle layers of each plate")
      .integer("regions", t.regions, "Measurement slabs at heights H (k+1)/(regions+1)")
      .text("orientations", o.orientations, "all, plate normals (x,y,z) or normal:direction pairs (z:x,...)")
      .number("time_step_safety", t.time_step_safety, "Time step as a fraction of sqrt(m/k)")
      .integer("threads", t.threads, "OpenMP threads (0 = all cores)")
      .boolean("relax.enabled", t.relax, "Relax the bonded structure first (§2.2: velocities zeroed after each step)")
      .boolean("relax.settle", t.settle, "Settle the test set-up with the same procedure before loading")
      .integer("relax.max_steps", t.relax_options.max_steps, "Step limit of the relaxation")
      .integer("relax.check_interval", t.relax_options.check_interval, "Steps between two checks")
      .number("relax.min_decrease", t.relax_options.min_decrease,
              "Relative decrease of the mean unbalanced force that counts as progress")
      .integer("relax.patience", t.relax_options.patience, "Checks without progress that end the relaxation")
      .boolean("output.plots", o.plots, "Draw the PNG plots");
  return s;
}

}  // namespace

std::string shear_config_reference() {
  ShearCliOptions o;
  o.test.threads = 1;
  return shear_config_schema("test shear", o).markdown();
}

// Adds the flags; the returned function (call it in the callback) reads --config, then overrides
// with the flags given, and fills the test options, the orientation spec and the plot switch.
std::function<void(mechanics::OscillatoryShearOptions&, std::string&, bool&)> add_shear_flags(CLI::App* cmd,
                                                                                       const std::string& command) {
  auto flags = std::make_shared<ShearCliOptions>();
  flags->test.threads = 1;
  auto& ft = flags->test;
  cmd->add_option("--config", flags->config, "TOML file with any parameter (docs/shear.md); flags override it");
  cmd->add_option("--normal-stiffness", ft.normal_stiffness, "Particle normal stiffness k_n [N/m]")
      ->capture_default_str();
  cmd->add_option("--shear-stiffness", ft.shear_stiffness, "Particle shear stiffness k_s [N/m]")->capture_default_str();
  cmd->add_option("--normal-strength", ft.normal_strength, "Bond normal strength F_nB [N]")->capture_default_str();
  cmd->add_option("--shear-strength", ft.shear_strength, "Bond shear strength F_sB [N]")->capture_default_str();
  cmd->add_option("--friction", ft.friction, "Friction of unbonded contacts [-]")->capture_default_str();
  cmd->add_option("--damping", ft.damping, "Local damping coefficient alpha")->capture_default_str();
  cmd->add_option("--density", ft.density, "Particle density [kg/m^3] (when the file has none)")->capture_default_str();
  cmd->add_option("--stiffness-rule", ft.stiffness_rule,
                  "particle: PFC particle stiffnesses (contacts and bonds act with k/2); contact: as given")
      ->capture_default_str();
  cmd->add_option("--cycles", ft.cycles, "Oscillation cycles")->capture_default_str();
  cmd->add_option("--amplitude", ft.amplitude, "Largest plate deflection / box edge [-] (last cycle)")
      ->capture_default_str();
  cmd->add_option("--steps-per-cycle", ft.steps_per_cycle, "Steps per cycle (quasi-static loading rate)")
      ->capture_default_str();
  cmd->add_option("--samples-per-cycle", ft.samples_per_cycle, "Stress samples per cycle (multiple of 4)")
      ->capture_default_str();
  cmd->add_option("--plate-layers", ft.plate_layers, "Particle layers of each plate")->capture_default_str();
  cmd->add_option("--regions", ft.regions, "Measurement slabs")->capture_default_str();
  cmd->add_option("--orientations", flags->orientations,
                  "all (six), plate normals (x,y,z: both shear directions each) or pairs normal:direction (z:x)")
      ->capture_default_str();
  cmd->add_option("--relax-max-steps", ft.relax_options.max_steps, "Step limit of the §2.2 relaxation")
      ->capture_default_str();
  cmd->add_flag("--no-relax", flags->no_relax, "Shear the structure as it is (no §2.2 relaxation, no settling)");
  cmd->add_option("--threads", ft.threads, "OpenMP threads (0 = all cores)")->capture_default_str();
  return [cmd, flags, command](mechanics::OscillatoryShearOptions& out, std::string& orientations, bool& plots) {
    auto given = [&](const char* name) { return cmd->count(name) > 0; };
    ShearCliOptions r;
    r.test.threads = 1;
    if (!flags->config.empty()) shear_config_schema(command, r).read_file(flags->config);
    const auto& f = flags->test;
    auto& t = r.test;
    if (given("--normal-stiffness")) t.normal_stiffness = f.normal_stiffness;
    if (given("--shear-stiffness")) t.shear_stiffness = f.shear_stiffness;
    if (given("--normal-strength")) t.normal_strength = f.normal_strength;
    if (given("--shear-strength")) t.shear_strength = f.shear_strength;
    if (given("--friction")) t.friction = f.friction;
    if (given("--damping")) t.damping = f.damping;
    if (given("--density")) t.density = f.density;
    if (given("--stiffness-rule")) t.stiffness_rule = f.stiffness_rule;
    if (given("--cycles")) t.cycles = f.cycles;
    if (given("--amplitude")) t.amplitude = f.amplitude;
    if (given("--steps-per-cycle")) t.steps_per_cycle = f.steps_per_cycle;
    if (given("--samples-per-cycle")) t.samples_per_cycle = f.samples_per_cycle;
    if (given("--plate-layers")) t.plate_layers = f.plate_layers;
    if (given("--regions")) t.regions = f.regions;
    if (given("--orientations")) r.orientations = flags->orientations;
    if (given("--relax-max-steps")) t.relax_options.max_steps = f.relax_options.max_steps;
    if (given("--threads")) t.threads = f.threads;
    if (flags->no_relax) t.relax = t.settle = false;
    t.orientations = mechanics::shear_orientations(r.orientations);
    mechanics::validate(t);
    out = t;
    orientations = r.orientations;
    plots = r.plots;
  };
}

nlohmann::json shear_parameters_json(const mechanics::OscillatoryShearOptions& t, const std::string& orientations) {
  return {{"normal_stiffness", t.normal_stiffness},
          {"shear_stiffness", t.shear_stiffness},
          {"normal_strength", t.normal_strength},
          {"shear_strength", t.shear_strength},
          {"friction", t.friction},
          {"damping", t.damping},
          {"density", t.density},
          {"stiffness_rule", t.stiffness_rule},
          {"cycles", t.cycles},
          {"amplitude", t.amplitude},
          {"steps_per_cycle", t.steps_per_cycle},
          {"samples_per_cycle", t.samples_per_cycle},
          {"plate_layers", t.plate_layers},
          {"regions", t.regions},
          {"orientations", orientations},
          {"time_step_safety", t.time_step_safety},
          {"relax", t.relax},
          {"settle", t.settle},
          {"relax_max_steps", t.relax_options.max_steps},
          {"relax_check_interval", t.relax_options.check_interval},
          {"relax_min_decrease", t.relax_options.min_decrease},
          {"relax_patience", t.relax_options.patience},
          {"threads", t.threads}};
}

namespace {

std::string stress_strain_csv(const mechanics::OscillatoryShearResult& result, int regions) {
  std::string csv = io::csv_header(mechanics::shear_sample_columns({}, regions), "orientation");
  for (const auto& run : result.runs)
    io::append_csv_rows(csv, mechanics::shear_sample_columns(run.samples, regions),
                        mechanics::orientation_name(run.orientation));
  return csv;
}

std::string cycles_csv(const mechanics::OscillatoryShearResult& result) {
  std::string csv = io::csv_header(mechanics::shear_cycle_columns({}), "orientation");
  for (const auto& run : result.runs)
    io::append_csv_rows(csv, mechanics::shear_cycle_columns(run.cycles), mechanics::orientation_name(run.orientation));
  return csv;
}

nlohmann::json shear_result_json(const mechanics::OscillatoryShearResult& result) {
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

}  // namespace

void add_test_shear(CLI::App& test) {
  struct Options {
    std::string in, out;
    bool quiet = false, no_plots = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = test.add_subcommand(
      "shear", "Oscillatory shear test of a bonded model: storage modulus G' for six orientations (docs/shear.md)");
  cmd->add_option("in", opt->in, "Bonded model (a file with bonds, e.g. from packlab bond)")->required();
  cmd->add_option("--out", opt->out, "Output folder")->required();
  auto apply = add_shear_flags(cmd, "test shear");
  cmd->add_flag("--no-plots", opt->no_plots, "Do not draw the PNG plot");
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->callback([opt, apply] {
    mechanics::OscillatoryShearOptions options;
    std::string orientations;
    bool plots = true;
    apply(options, orientations, plots);
    const Packing packing = io::read_packing(opt->in);
    const std::filesystem::path dir = opt->out;
    io::ensure_directory(dir);
    const long per_run = options.steps_per_cycle * options.cycles;
    Progress progress("test shear", per_run * static_cast<long>(options.orientations.size()), !opt->quiet);
    std::string current;
    long offset = 0, last = 0;
    options.progress = [&](const std::string& stage, long done, long) {
      if (stage == "relax") {
        progress.update(0, fmt::format("relaxing, step {}", done));
        return;
      }
      if (stage != current) {
        if (!current.empty()) offset += last;
        current = stage;
      }
      last = done;
      progress.update(offset + done, "orientation " + stage);
    };
    const mechanics::OscillatoryShearResult result = mechanics::run_oscillatory_shear(packing, options);
    progress.finish();

    io::write_text_atomically(dir / "stress_strain.csv", stress_strain_csv(result, options.regions));
    io::write_text_atomically(dir / "cycles.csv", cycles_csv(result));
    io::WriteOptions w;
    w.comment = fmt::format("packlab test shear {}: relaxed structure that was tested", opt->in);
    io::write_packing(result.relaxed_packing, dir / "relaxed.vtu", w);
    nlohmann::json report = io::report_header("test shear");
    report["input"] = opt->in;
    report["particles"] = packing.size();
    report["bonds"] = packing.bonds.size();
    report["parameters"] = shear_parameters_json(options, orientations);
    report.update(shear_result_json(result));
    io::write_report(dir / "report.json", report);
    io::PlotOptions plot;
    plot.enabled = !opt->no_plots && plots;
    io::make_plot("shear", {(dir / "stress_strain.csv").string()}, dir / "shear.png", plot);
    if (!opt->quiet) {
      for (const auto& r : result.runs)
        fmt::print("{}: G' = {:.4g} Pa (|G*| {:.4g} Pa, plate {:.4g} Pa), phase angle {:.3g} rad, {} bonds broken\n",
                   mechanics::orientation_name(r.orientation), r.storage_modulus, r.complex_modulus,
                   r.plate_storage_modulus, r.phase_angle, r.broken_bonds);
      fmt::print("G' = {:.4g} +- {:.3g} Pa over {} orientations, phase angle {:.3g} rad; {:.1f} s ({:.3g} "
                 "particle-steps/s); wrote {}\n",
                 result.storage_modulus_mean, result.storage_modulus_std, result.runs.size(), result.phase_angle_mean,
                 result.seconds, result.seconds > 0 ? result.particle_steps / result.seconds : 0.0, dir.string());
    }
  });
}

}  // namespace packlab::cli
