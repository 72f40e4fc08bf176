// packlab generate scrm [--config FILE.toml] --phi X --particles N [sizes as generate ls] [--growth-rate G]
//   [--window 0.02] [--max-trials 150] [--adaptive] [--blocks-per-cycle 5] [--shakes-per-cycle 1]
//   [--final-shakes 10] [--seed S] [--checkpoint-seconds S] --out DIR
// packlab generate scrm --resume DIR
// Shaking collective rearrangement model: LS growth alternated with global shakes, then final
// shakes at X. Writes the same files as generate ls, and checkpoint.bin (after every LS segment
// with its shakes and every final shake, every --checkpoint-seconds and at the end; --resume
// DIR goes on from it, cli/checkpoint.hpp).
#include <fmt/format.h>

#include <chrono>
#include <memory>
#include <optional>

#include "packlab/cli/commands.hpp"
#include "packlab/cli/scrm_common.hpp"
#include "packlab/core/binary_io.hpp"
#include "packlab/core/progress.hpp"
#include "packlab/generate/overlap_check.hpp"
#include "packlab/generate/scrm.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/report.hpp"

namespace packlab::cli {

std::string scrm_config_reference() {
  io::ScrmOptions o;
  LsRunOptions run;
  return ls_run_schema(io::scrm_options(o), run, true).markdown();
}

void add_generate_scrm(CLI::App& generate) {
  struct Options {
    io::ScrmOptions scrm;
    LsRunOptions run;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = generate.add_subcommand(
      "scrm", "Shaking collective rearrangement: LS growth alternated with Monte-Carlo shaking, then final shakes");
  add_ls_run_options(*cmd, opt->run, io::scrm_options(opt->scrm), true);
  cmd->callback([opt] {
    const auto t0 = std::chrono::steady_clock::now();
    resolve_ls_run_options(opt->run);
    const io::ScrmOptions& o = opt->scrm;
    LsRunOptions& run = opt->run;
    const generate::ScrmParams sp = o.params();
    run.flags->schema().validate();
    io::ensure_directory(run.out);
    // The run and its generator: new, or as saved between two steps.
    Random rng(o.seed);
    std::optional<generate::ScrmRun> scrm;
    if (run.resumed) {
      scrm.emplace(generate::ScrmRun::load_state(run.resumed->state, sp));
      binary::read_random(run.resumed->state, rng);
    } else {
      const generate::LsStart start = generate::make_ls_start(o.particles, o.classes(), o.radius, o.phi, rng);
      scrm.emplace(generate::LsSimulation(start.box, start.points, start.unit_radius, sp.ls, rng), sp);
    }
    CheckpointWriter checkpoint(run.out, run.flags->schema(), "", run.checkpoint_seconds);
    const auto save = [&](std::ostream& out) {
      scrm->save_state(out);
      binary::write_random(out, rng);
    };
    Progress progress("generate scrm", 0, !run.quiet);
    const auto on_progress = [&](const generate::LsStatus& ls, const generate::ShakeStats& s) {
      progress.update(ls.blocks + s.sweeps, fmt::format("phi {:.5f}, {} global shakes", ls.volume_fraction, s.sweeps));
    };
    while (scrm->step(rng, on_progress)) checkpoint.write_if_due(save);
    checkpoint.write(save);
    progress.finish();
    const generate::ScrmResult r = scrm->result();
    const std::filesystem::path dir(run.out);
    write_packing_outputs(r.packing, dir,
                          fmt::format("packlab {} generate scrm phi={:.8f} N={} growth_rate={:g} move_rule={} "
                                      "window={:g} final_shakes={} seed={}",
                                      io::version(), r.packing.volume_fraction(), r.packing.size(), sp.ls.growth_rate,
                                      sp.shake.move_rule, sp.shake.window, sp.final_shakes, o.seed));
    nlohmann::json report = io::report_header("generate scrm");
    report["parameters"] = ls_parameters(o);
    report["parameters"]["move_rule"] = sp.shake.move_rule;
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
    report["results"]["rdf"] = rdf_of(r.packing, dir, run.rdf.dr, run.rdf.r_max, !run.no_plots);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    report["seconds"] = seconds;
    io::write_report(dir / "report.json", report);
    if (!run.quiet)
      fmt::print("phi {:.6f}: {} collisions, {} global shakes ({} of {} trial moves executed); wrote {} in {:.2f} s\n",
                 r.packing.volume_fraction(), r.ls.collisions, r.shake.sweeps, r.shake.moves, r.shake.trials, run.out,
                 seconds);
  });
}

}  // namespace packlab::cli
