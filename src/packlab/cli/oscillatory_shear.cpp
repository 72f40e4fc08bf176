// packlab test shear IN [--config FILE] [every option of io::shear_test_options as a flag:
//   --normal-stiffness 100 --shear-stiffness 10 --cycles 10 --amplitude 0.001
//   --orientations all|x,y,z|z:x,... --relax-max-steps N ...] --out DIR
// The oscillatory shear test of doh-elastic-properties §2.4 on a bonded model (any file with
// bonds: `packlab bond` output, lattices included): §2.2 relaxation, plates from the periodic
// repetition, ten cycles of linearly increasing amplitude, G' = |G*| cos(delta) per orientation.
// Writes DIR/stress_strain.csv (every sample), DIR/cycles.csv (per cycle and orientation),
// DIR/shear.png (Fig. 4), DIR/relaxed.vtu (the tested structure with its bonds) and
// DIR/report.json.
#include "packlab/mechanics/oscillatory_shear.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>

#include "packlab/cli/commands.hpp"
#include "packlab/cli/options.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/progress.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/options.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/plot.hpp"
#include "packlab/io/report.hpp"
#include "packlab/io/table.hpp"

namespace packlab::cli {

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
  CommandParts parts;
  parts.input = "Bonded model (a file with bonds, e.g. from packlab bond)";
  parts.output = "Output folder";
  parts.plots = true;
  add_option_command(
      test, "shear",
      "Oscillatory shear test of a bonded model: storage modulus G' for six orientations (docs/shear.md)",
      io::shear_test_options, parts, [](const OptionCommand<io::ShearTestRun>& c) {
        mechanics::OscillatoryShearOptions options = c.settings.test;
        mechanics::validate(options);
        const Packing packing = io::read_packing(c.in);
        const std::filesystem::path dir = c.out;
        io::ensure_directory(dir);
        const long per_run = options.steps_per_cycle * options.cycles;
        const auto orientations = mechanics::shear_orientations(options.orientations);
        Progress progress("test shear", per_run * static_cast<long>(orientations.size()), !c.quiet);
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
        w.comment = fmt::format("packlab test shear {}: relaxed structure that was tested", c.in);
        io::write_packing(result.relaxed_packing, dir / "relaxed.vtu", w);
        nlohmann::json report = io::report_header("test shear");
        report["input"] = c.in;
        report["particles"] = packing.size();
        report["bonds"] = packing.bonds.size();
        report["parameters"] = c.flags->schema().json();
        report.update(shear_result_json(result));
        io::write_report(dir / "report.json", report);
        io::PlotOptions plot;
        plot.enabled = !c.no_plots && c.settings.plots;
        io::make_plot("shear", {(dir / "stress_strain.csv").string()}, dir / "shear.png", plot);
        if (!c.quiet) {
          for (const auto& r : result.runs)
            fmt::print(
                "{}: G' = {:.4g} Pa (|G*| {:.4g} Pa, plate {:.4g} Pa), phase angle {:.3g} rad, {} bonds broken\n",
                mechanics::orientation_name(r.orientation), r.storage_modulus, r.complex_modulus,
                r.plate_storage_modulus, r.phase_angle, r.broken_bonds);
          fmt::print(
              "G' = {:.4g} +- {:.3g} Pa over {} orientations, phase angle {:.3g} rad; {:.1f} s ({:.3g} "
              "particle-steps/s); wrote {}\n",
              result.storage_modulus_mean, result.storage_modulus_std, result.runs.size(), result.phase_angle_mean,
              result.seconds, result.seconds > 0 ? result.particle_steps / result.seconds : 0.0, dir.string());
        }
      });
}

}  // namespace packlab::cli
