// packlab test shear IN [--config FILE] [every option of io::shear_test_options as a flag:
//   --normal-stiffness 100 --shear-stiffness 10 --cycles 10 --amplitude 0.001
//   --orientations all|x,y,z|z:x,... --relax-max-steps N ...] --out DIR
// The oscillatory shear test of doh-elastic-properties §2.4 on a bonded model (any file with
// bonds: `packlab bond` output, lattices included): §2.2 relaxation, plates from the periodic
// repetition, ten cycles of linearly increasing amplitude, G' = |G*| cos(delta) per orientation.
// Writes DIR/stress_strain.csv (every sample), DIR/cycles.csv (per cycle and orientation),
// DIR/shear.png (Fig. 4), DIR/relaxed.vtu (the tested structure with its bonds) and
// DIR/report.json.
// packlab test shear --resume DIR [--threads T] [--adapt-threads=false]
// The dynamic solver writes DIR/checkpoint.bin after the relaxation and after each orientation
// (at most every --checkpoint-seconds, and at the end; cli/checkpoint.hpp); --resume DIR runs
// the orientations still missing and writes the same files as an uninterrupted run (an
// orientation that was interrupted starts again). The static solver takes no checkpoints.
#include "packlab/mechanics/oscillatory_shear.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>

#include "packlab/cli/checkpoint.hpp"
#include "packlab/cli/commands.hpp"
#include "packlab/cli/options.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/progress.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/mechanics_report.hpp"
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

}  // namespace

void add_test_shear(CLI::App& test) {
  CLI::App* cmd = add_option_command(
      test, "shear",
      "Oscillatory shear test of a bonded model: storage modulus G' for six orientations (docs/shear.md)",
      io::shear_test_options,
      {.input = "Bonded model (a file with bonds, e.g. from packlab bond)",
       .output = "Output folder",
       .plots = true,
       .resumable = true},
      [](OptionCommand<io::ShearTestRun>& c) {
        mechanics::OscillatoryShearOptions options = c.settings.test;
        mechanics::validate(options);
        const Packing packing = io::read_packing(c.in);
        const std::filesystem::path dir = c.out;
        const io::OutputFolder folder(dir);  // removed again when the model is refused
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
        CheckpointWriter checkpoint(dir, c.flags->schema(), c.in, c.settings.checkpoint_seconds);
        options.checkpoint = [&](const std::function<void(std::ostream&)>& state, bool end) {
          end ? checkpoint.write(state) : checkpoint.write_if_due(state);
        };
        if (c.resumed) options.resume = &c.resumed->state;
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
        report.update(io::oscillatory_shear_summary(result));
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
          if (c.settings.test.solver == "static")
            fmt::print(
                "static solver: one linear solve per orientation (no inertia or damping: phase angle 0 by "
                "construction)\n");
        }
      });
  cmd->footer(
      "Checkpoints (--checkpoint-seconds, --resume): the dynamic solver writes one after the relaxation and after "
      "each orientation; --solver static takes none (one linear solve per orientation).");
}

}  // namespace packlab::cli
