// packlab shake IN [--config FILE.toml] --sweeps M [--window 0.02] [--max-trials 150] [--adaptive] [--seed S]
//   [--rdf-dr X] [--rdf-rmax X] --out DIR
// Monte-Carlo shaking of any hard-sphere packing: M global shakes. Writes DIR/packing.xyz, .vtu,
// the RDF tables and plots of the shaken packing and report.json (with the contact value before).
#include <fmt/format.h>

#include <chrono>
#include <memory>

#include "packlab/cli/commands.hpp"
#include "packlab/cli/options.hpp"
#include "packlab/cli/scrm_common.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/progress.hpp"
#include "packlab/generate/overlap_check.hpp"
#include "packlab/generate/shake.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/options.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/report.hpp"

namespace packlab::cli {

namespace {

// The method's options and the command's RDF of the result.
io::ConfigSchema shake_schema(io::ShakeOptions& o, analyze::RdfParams& rdf) {
  return io::shake_options(o).append(rdf_output_options("shake", rdf));
}

}  // namespace

std::string shake_config_reference() {
  io::ShakeOptions o;
  analyze::RdfParams rdf;
  return shake_schema(o, rdf).markdown();
}

void add_shake(CLI::App& app) {
  struct Options {
    std::string in, out;
    io::ShakeOptions o;
    analyze::RdfParams rdf;
    std::unique_ptr<OptionFlags> flags;
    bool no_plots = false, quiet = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("shake", "Monte-Carlo shaking of a hard-sphere packing (global shakes)");
  cmd->add_option("in", opt->in, "Input packing (no overlaps)")->required();
  opt->flags = std::make_unique<OptionFlags>(cmd, shake_schema(opt->o, opt->rdf));
  cmd->add_option("--out", opt->out, "Output folder")->required();
  cmd->add_flag("--no-plots", opt->no_plots, "Do not write PNG plots");
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->callback([opt] {
    const auto t0 = std::chrono::steady_clock::now();
    opt->flags->load();
    opt->o.shake.validate();
    opt->flags->schema().validate();
    Packing packing = io::read_packing(opt->in);
    io::ensure_directory(opt->out);
    analyze::Rdf before(opt->rdf);
    before.compute(packing);
    Random rng(opt->o.seed);
    generate::Shaker shaker(packing, opt->o.shake);
    Progress progress("shake", opt->o.sweeps, !opt->quiet);
    shaker.sweeps(opt->o.sweeps, rng, [&](const generate::ShakeStats& s) {
      progress.update(s.sweeps, fmt::format("{:.3g} trial moves/s", static_cast<double>(s.trials) / s.seconds));
    });
    progress.finish();
    const generate::ShakeStats& s = shaker.stats();
    const std::filesystem::path dir(opt->out);
    write_packing_outputs(packing, dir,
                          fmt::format("packlab {} shake {} sweeps={} window={:g} max_trials={} seed={}", io::version(),
                                      opt->in, opt->o.sweeps, opt->o.shake.window, opt->o.shake.max_trials, opt->o.seed));
    nlohmann::json report = io::report_header("shake");
    report["parameters"] = io::shake_options(opt->o).json();
    report["parameters"]["in"] = opt->in;
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
    report["results"]["rdf"] = rdf_of(packing, dir, opt->rdf.dr, opt->rdf.r_max, !opt->no_plots);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    report["seconds"] = seconds;
    io::write_report(dir / "report.json", report);
    if (!opt->quiet)
      fmt::print("{} global shakes: {} of {} trial moves executed ({:.3g} trial moves/s), contact value {:.4g} -> {:.4g}; "
                 "wrote {} in {:.2f} s\n",
                 s.sweeps, s.moves, s.trials, static_cast<double>(s.trials) / s.seconds, before.contact_value(0, 0),
                 report["results"]["rdf"]["contact_value"].get<double>(), opt->out, seconds);
  });
}

}  // namespace packlab::cli
