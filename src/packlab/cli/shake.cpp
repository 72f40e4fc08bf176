// packlab shake IN [--config FILE.toml] --sweeps M [--window 0.02] [--max-trials 150] [--adaptive] [--seed S]
//   [--rdf-dr X] [--rdf-r-max X] [--checkpoint-seconds S] --out DIR
// packlab shake --resume DIR
// Monte-Carlo shaking of any hard-sphere packing: M global shakes. Writes DIR/packing.xyz, .vtu,
// the RDF tables and plots of the shaken packing, report.json (with the contact value before)
// and checkpoint.bin (between two global shakes, every --checkpoint-seconds and at the end;
// --resume DIR goes on from it with the saved settings and the input file, cli/checkpoint.hpp).
#include "packlab/generate/shake.hpp"

#include <fmt/format.h>

#include <chrono>
#include <memory>

#include "packlab/cli/checkpoint.hpp"
#include "packlab/cli/commands.hpp"
#include "packlab/cli/options.hpp"
#include "packlab/cli/scrm_common.hpp"
#include "packlab/core/binary_io.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/progress.hpp"
#include "packlab/generate/overlap_check.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/options.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/report.hpp"

namespace packlab::cli {

namespace {

// The method's options and the command's RDF of the result.
struct ShakeRun {
  io::ShakeOptions o;
  analyze::RdfParams rdf;
};
io::ConfigSchema shake_schema(ShakeRun& r) { return io::shake_options(r.o).append(rdf_output_options("shake", r.rdf)); }

}  // namespace

std::string shake_config_reference() { return option_reference(shake_schema); }

void add_shake(CLI::App& app) {
  add_option_command(
      app, "shake", "Monte-Carlo shaking of a hard-sphere packing (global shakes)", shake_schema,
      {.input = "Input packing (no overlaps)", .output = "Output folder", .plots = true, .resumable = true},
      [](OptionCommand<ShakeRun>& c) {
        const auto t0 = std::chrono::steady_clock::now();
        const ShakeRun& run = c.settings;
        run.o.shake.validate();
        Packing packing = io::read_packing(c.in);
        io::ensure_directory(c.out);
        analyze::Rdf before(run.rdf);
        before.compute(packing);
        Random rng(run.o.seed);
        generate::Shaker shaker(packing, run.o.shake);
        if (c.resumed) {  // the positions, statistics and generator between two sweeps
          shaker.load_state(c.resumed->state);
          binary::read_random(c.resumed->state, rng);
        }
        CheckpointWriter checkpoint(c.out, c.flags->schema(), c.in, run.o.checkpoint_seconds);
        const auto save = [&](std::ostream& out) {
          shaker.save_state(out);
          binary::write_random(out, rng);
        };
        Progress progress("shake", run.o.sweeps, !c.quiet);
        while (shaker.stats().sweeps < run.o.sweeps) {
          shaker.sweep(rng);
          const generate::ShakeStats& s = shaker.stats();
          progress.update(s.sweeps, fmt::format("{:.3g} trial moves/s", static_cast<double>(s.trials) / s.seconds));
          checkpoint.write_if_due(save);
        }
        checkpoint.write(save);
        progress.finish();
        const generate::ShakeStats& s = shaker.stats();
        const std::filesystem::path dir(c.out);
        write_packing_outputs(
            packing, dir,
            fmt::format("packlab {} shake {} sweeps={} move_rule={} window={:g} max_trials={} seed={}", io::version(),
                        c.in, run.o.sweeps, run.o.shake.move_rule, run.o.shake.window, run.o.shake.max_trials,
                        run.o.seed));
        nlohmann::json report = io::report_header("shake");
        io::ShakeOptions reported = run.o;
        report["parameters"] = io::shake_options(reported).json();
        report["parameters"]["in"] = c.in;
        report["results"] = {{"volume_fraction", packing.volume_fraction()},
                             {"visits", s.visits},
                             {"trial_moves", s.trials},
                             {"moves", s.moves},
                             {"shake_seconds", s.seconds},
                             {"trial_moves_per_second", static_cast<double>(s.trials) / s.seconds},
                             {"mean_step_over_radius", s.mean_step},
                             {"final_window", s.window},
                             {"contact_value_before", before.contact_value(0, 0)},
                             {"min_contact_ratio", generate::min_contact_ratio(packing)}};
        report["results"]["rdf"] = rdf_of(packing, dir, run.rdf.dr, run.rdf.r_max, !c.no_plots);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        report["seconds"] = seconds;
        io::write_report(dir / "report.json", report);
        if (!c.quiet)
          fmt::print(
              "{} global shakes: {} of {} trial moves executed ({:.3g} trial moves/s), contact value {:.4g} -> {:.4g}; "
              "wrote {} in {:.2f} s\n",
              s.sweeps, s.moves, s.trials, static_cast<double>(s.trials) / s.seconds, before.contact_value(0, 0),
              report["results"]["rdf"]["contact_value"].get<double>(), c.out, seconds);
      });
}

}  // namespace packlab::cli
