// packlab generate scrm --phi X --particles N [sizes as generate ls] [--growth-rate G]
//   [--window 0.02] [--max-trials 150] [--adaptive] [--blocks-per-cycle 5] [--shakes-per-cycle 1]
//   [--final-shakes 10] [--seed S] --out DIR
// Shaking collective rearrangement model: LS growth alternated with global shakes, then final
// shakes at X. Writes the same files as generate ls.
#include <fmt/format.h>

#include <chrono>
#include <memory>

#include "packlab/cli/commands.hpp"
#include "packlab/cli/scrm_common.hpp"
#include "packlab/core/progress.hpp"
#include "packlab/generate/overlap_check.hpp"
#include "packlab/generate/scrm.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/report.hpp"

namespace packlab::cli {

void add_generate_scrm(CLI::App& generate) {
  struct Options {
    LsRunOptions run;
    generate::ShakeParams shake;
    long blocks_per_cycle = 5, shakes_per_cycle = 1, final_shakes = 10;
  };
  auto opt = std::make_shared<Options>();
  opt->run.phi = 0.6;
  auto* cmd = generate.add_subcommand(
      "scrm", "Shaking collective rearrangement: LS growth alternated with Monte-Carlo shaking, then final shakes");
  add_ls_options(*cmd, opt->run);
  cmd->add_option("--window", opt->shake.window, "Shake window R_sh in units of the particle radius")
      ->capture_default_str();
  cmd->add_option("--max-trials", opt->shake.max_trials, "Trials per visit N_sh")->capture_default_str();
  cmd->add_flag("--adaptive", opt->shake.adaptive, "Adapt the shake window to the free distance");
  cmd->add_option("--blocks-per-cycle", opt->blocks_per_cycle, "LS blocks between shakes")->capture_default_str();
  cmd->add_option("--shakes-per-cycle", opt->shakes_per_cycle, "Global shakes after each LS segment")
      ->capture_default_str();
  cmd->add_option("--final-shakes", opt->final_shakes, "Global shakes at the target volume fraction")
      ->capture_default_str();
  cmd->callback([opt] {
    const auto t0 = std::chrono::steady_clock::now();
    LsRunOptions& o = opt->run;
    generate::ScrmParams sp;
    sp.ls = o.ls;
    sp.ls.target_volume_fraction = o.phi;
    sp.shake = opt->shake;
    sp.blocks_per_cycle = opt->blocks_per_cycle;
    sp.shakes_per_cycle = opt->shakes_per_cycle;
    sp.final_shakes = opt->final_shakes;
    sp.validate();
    io::ensure_directory(o.out);
    Random rng(o.seed);
    const generate::LsStart start = generate::make_ls_start(o.particles, o.classes(), o.radius, o.phi, rng);
    generate::LsSimulation sim(start.box, start.points, start.unit_radius, sp.ls, rng);
    Progress progress("generate scrm", 0, !o.quiet);
    const generate::ScrmResult r = run_scrm(sim, sp, rng, [&](const generate::LsStatus& ls, const generate::ShakeStats& s) {
      progress.update(ls.blocks + s.sweeps, fmt::format("phi {:.5f}, {} global shakes", ls.volume_fraction, s.sweeps));
    });
    progress.finish();
    const std::filesystem::path dir(o.out);
    write_packing_outputs(r.packing, dir,
                          fmt::format("packlab {} generate scrm phi={:.8f} N={} growth_rate={:g} window={:g} "
                                      "final_shakes={} seed={}",
                                      io::version(), r.packing.volume_fraction(), r.packing.size(), sp.ls.growth_rate,
                                      sp.shake.window, sp.final_shakes, o.seed));
    nlohmann::json report = io::report_header("generate scrm");
    report["parameters"] = o.parameters();
    report["parameters"]["window"] = sp.shake.window;
    report["parameters"]["max_trials"] = sp.shake.max_trials;
    report["parameters"]["adaptive"] = sp.shake.adaptive;
    report["parameters"]["blocks_per_cycle"] = sp.blocks_per_cycle;
    report["parameters"]["shakes_per_cycle"] = sp.shakes_per_cycle;
    report["parameters"]["final_shakes"] = sp.final_shakes;
    report["results"] = {{"volume_fraction", r.packing.volume_fraction()},
                         {"ls_stop", generate::ls_stop_name(r.ls.stop)},
                         {"collisions", r.ls.collisions},
                         {"ls_seconds", r.ls.seconds},
                         {"collisions_per_second", static_cast<double>(r.ls.collisions) / r.ls.seconds},
                         {"events_per_second", static_cast<double>(r.ls.events()) / r.ls.seconds},
                         {"cycles", r.cycles},
                         {"global_shakes", r.shake.sweeps},
                         {"trial_moves", r.shake.trials},
                         {"moves", r.shake.moves},
                         {"shake_seconds", r.shake.seconds},
                         {"trial_moves_per_second", static_cast<double>(r.shake.trials) / r.shake.seconds},
                         {"mean_step_over_radius", r.shake.mean_step},
                         {"final_window", r.shake.window},
                         {"min_contact_ratio", generate::min_contact_ratio(r.packing)}};
    report["results"]["rdf"] = rdf_of(r.packing, dir, o.rdf_dr, o.rdf_rmax, !o.no_plots);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    report["seconds"] = seconds;
    io::write_report(dir / "report.json", report);
    if (!o.quiet)
      fmt::print("phi {:.6f}: {} collisions, {} global shakes ({} of {} trial moves executed); wrote {} in {:.2f} s\n",
                 r.packing.volume_fraction(), r.ls.collisions, r.shake.sweeps, r.shake.moves, r.shake.trials, o.out,
                 seconds);
  });
}

}  // namespace packlab::cli
