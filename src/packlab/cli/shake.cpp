// packlab shake IN --sweeps M [--window 0.02] [--max-trials 150] [--adaptive] [--seed S] --out DIR
// Monte-Carlo shaking of any hard-sphere packing: M global shakes. Writes DIR/packing.xyz, .vtu,
// the RDF tables and plots of the shaken packing and report.json (with the contact value before).
#include <fmt/format.h>

#include <chrono>
#include <memory>

#include "packlab/cli/commands.hpp"
#include "packlab/cli/scrm_common.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/progress.hpp"
#include "packlab/generate/overlap_check.hpp"
#include "packlab/generate/shake.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/report.hpp"

namespace packlab::cli {

void add_shake(CLI::App& app) {
  struct Options {
    std::string in, out;
    long sweeps = 10;
    generate::ShakeParams shake;
    std::uint64_t seed = 1;
    double rdf_dr = 0.01, rdf_rmax = 8.0;
    bool no_plots = false, quiet = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("shake", "Monte-Carlo shaking of a hard-sphere packing (global shakes)");
  cmd->add_option("in", opt->in, "Input packing (no overlaps)")->required();
  cmd->add_option("--sweeps", opt->sweeps, "Global shakes M (each visits every particle once)")->capture_default_str();
  cmd->add_option("--window", opt->shake.window, "Shake window R_sh in units of the particle radius")
      ->capture_default_str();
  cmd->add_option("--max-trials", opt->shake.max_trials, "Trials per visit N_sh")->capture_default_str();
  cmd->add_flag("--adaptive", opt->shake.adaptive, "Adapt the shake window to the free distance");
  cmd->add_option("--seed", opt->seed, "Random seed")->capture_default_str();
  cmd->add_option("--rdf-dr", opt->rdf_dr, "RDF bin width in units of the largest radius")->capture_default_str();
  cmd->add_option("--rdf-rmax", opt->rdf_rmax, "RDF range in units of the largest radius")->capture_default_str();
  cmd->add_option("--out", opt->out, "Output folder")->required();
  cmd->add_flag("--no-plots", opt->no_plots, "Do not write PNG plots");
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->callback([opt] {
    const auto t0 = std::chrono::steady_clock::now();
    opt->shake.validate();
    require(opt->sweeps >= 0, "sweeps", static_cast<double>(opt->sweeps), ">= 0");
    Packing packing = io::read_packing(opt->in);
    io::ensure_directory(opt->out);
    analyze::RdfParams rp;
    rp.dr = opt->rdf_dr;
    rp.r_max = opt->rdf_rmax;
    analyze::Rdf before(rp);
    before.compute(packing);
    Random rng(opt->seed);
    generate::Shaker shaker(packing, opt->shake);
    Progress progress("shake", opt->sweeps, !opt->quiet);
    shaker.sweeps(opt->sweeps, rng, [&](const generate::ShakeStats& s) {
      progress.update(s.sweeps, fmt::format("{:.3g} trial moves/s", static_cast<double>(s.trials) / s.seconds));
    });
    progress.finish();
    const generate::ShakeStats& s = shaker.stats();
    const std::filesystem::path dir(opt->out);
    write_packing_outputs(packing, dir,
                          fmt::format("packlab {} shake {} sweeps={} window={:g} max_trials={} seed={}", io::version(),
                                      opt->in, opt->sweeps, opt->shake.window, opt->shake.max_trials, opt->seed));
    nlohmann::json report = io::report_header("shake");
    report["parameters"] = {{"in", opt->in},           {"sweeps", opt->sweeps},
                            {"window", opt->shake.window}, {"max_trials", opt->shake.max_trials},
                            {"adaptive", opt->shake.adaptive}, {"seed", opt->seed}};
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
    report["results"]["rdf"] = rdf_of(packing, dir, opt->rdf_dr, opt->rdf_rmax, !opt->no_plots);
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
