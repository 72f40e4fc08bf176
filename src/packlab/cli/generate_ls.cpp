// packlab generate ls [--config FILE.toml] [--phi X] --particles N [--sizes 1,0.313 (--number-fractions ... |
//   --volume-fractions ...)] [--radius R] [--growth-rate G] [--max-pressure P] [--events-per-block E] [--seed S]
//   [--rdf-dr X] [--rdf-r-max X] [--checkpoint-seconds S] --out DIR
// packlab generate ls --resume DIR
// Lubachevsky-Stillinger growth from random points to the volume fraction X, or to jamming
// without --phi. Writes DIR/packing.xyz, .vtu, ls_log.csv, rdf.csv (+ rdf_partial.csv),
// windows.csv, PNG plots, report.json and checkpoint.bin (between two blocks, every
// --checkpoint-seconds and at the end; --resume DIR goes on from it, cli/checkpoint.hpp).
#include <fmt/format.h>

#include <chrono>
#include <memory>
#include <optional>
#include <sstream>

#include "packlab/cli/commands.hpp"
#include "packlab/cli/scrm_common.hpp"
#include "packlab/core/binary_io.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/progress.hpp"
#include "packlab/generate/ls.hpp"
#include "packlab/generate/overlap_check.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/plot.hpp"
#include "packlab/io/report.hpp"

namespace packlab::cli {

nlohmann::json ls_parameters(const io::LsOptions& o) {
  const generate::SizeClasses c = o.classes();
  return {{"phi", o.phi},
          {"particles", o.particles},
          {"sizes", o.sizes},
          {"number_fractions", c.number_fractions()},
          {"counts", c.counts(o.particles)},
          {"radius_m", o.radius},
          {"growth_rate", o.ls.growth_rate},
          {"max_reduced_pressure", o.ls.max_reduced_pressure},
          {"events_per_block", o.ls.events_per_block},
          {"separation_boost", o.ls.separation_boost},
          {"seed", o.seed}};
}

io::ConfigSchema ls_run_schema(const io::ConfigSchema& method, LsRunOptions& run, bool resumable) {
  io::ConfigSchema all = method;
  all.append(rdf_output_options(method.command(), run.rdf));
  if (resumable) io::add_checkpoint_seconds(all, run.checkpoint_seconds);
  return all;
}

void add_ls_run_options(CLI::App& cmd, LsRunOptions& run, const io::ConfigSchema& method, bool resumable) {
  run.flags = std::make_unique<OptionFlags>(&cmd, ls_run_schema(method, run, resumable));
  CLI::Option* out = cmd.add_option("--out", run.out, "Output folder");
  if (resumable)
    cmd.add_option("--resume", run.resume,
                   "Continue the run whose checkpoint is in this folder, with its saved settings");
  else
    out->required();
  cmd.add_flag("--no-plots", run.no_plots, "Do not write PNG plots");
  cmd.add_flag("--quiet", run.quiet, "No progress output");
}

void resolve_ls_run_options(LsRunOptions& run) {
  if (!run.resume.empty()) {
    run.resumed.emplace(resume_saved_run(*run.flags, run.resume, "", run.out));
    run.out = run.resume;
    return;
  }
  if (run.out.empty()) fail_input("--out: required (the output folder), or --resume DIR");
  run.flags->load();
}

io::ConfigSchema rdf_output_options(const std::string& command, analyze::RdfParams& rdf) {
  io::ConfigSchema schema(command);
  schema.number("rdf.dr", rdf.dr, "RDF bin width in units of the largest radius")
      .range(ranges::positive)
      .command_only()
      .number("rdf.r_max", rdf.r_max, "RDF range in units of the largest radius")
      .range(ranges::positive)
      .command_only();
  return schema;
}

void write_packing_outputs(const Packing& packing, const std::filesystem::path& dir, const std::string& comment) {
  io::WriteOptions w;
  w.comment = comment;
  io::write_packing(packing, dir / "packing.xyz", w);
  io::write_packing(packing, dir / "packing.vtu", w);
}

nlohmann::json rdf_of(const Packing& packing, const std::filesystem::path& dir, double dr, double rmax, bool plots) {
  analyze::RdfParams p;
  p.dr = dr;
  p.r_max = rmax;
  analyze::Rdf rdf(p);
  rdf.compute(packing);
  return write_rdf_outputs(rdf, class_volume_fractions(packing, rdf.class_radius()), dir, rdf.classes() > 1, plots);
}

std::string ls_config_reference() {
  io::LsOptions o;
  LsRunOptions run;
  return ls_run_schema(io::ls_options(o), run, true).markdown();
}

void add_generate_ls(CLI::App& generate) {
  struct Options {
    io::LsOptions ls;
    LsRunOptions run;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = generate.add_subcommand(
      "ls", "Lubachevsky-Stillinger growth of hard spheres (event-driven MD) to a volume fraction or to jamming");
  add_ls_run_options(*cmd, opt->run, io::ls_options(opt->ls), true);
  cmd->callback([opt] {
    const auto t0 = std::chrono::steady_clock::now();
    resolve_ls_run_options(opt->run);
    const io::LsOptions& o = opt->ls;
    LsRunOptions& run = opt->run;
    const generate::SizeClasses classes = o.classes();
    generate::LsParams p = o.ls;
    p.target_volume_fraction = o.phi;
    p.validate();
    run.rdf.validate();
    run.flags->schema().validate();
    io::ensure_directory(run.out);
    // The simulation and its log so far: new, or as saved between two blocks.
    std::optional<generate::LsSimulation> sim;
    std::string log;
    if (run.resumed) {
      sim.emplace(generate::LsSimulation::load_state(run.resumed->state));
      binary::read_string(run.resumed->state, log, "log", 1ULL << 32);
    } else {
      Random rng(o.seed);
      const generate::LsStart start =
          generate::make_ls_start(o.particles, classes, o.radius, o.phi > 0 ? o.phi : 0.64, rng);
      sim.emplace(start.box, start.points, start.unit_radius, p, rng);
      log = "block,time,volume_fraction,reduced_pressure,collisions,transfers,seconds\n";
    }
    CheckpointWriter checkpoint(run.out, run.flags->schema(), "", run.checkpoint_seconds);
    const auto save = [&](std::ostream& out) {
      sim->save_state(out);
      binary::write_string(out, log);
    };
    Progress progress("generate ls", 0, !run.quiet);
    const generate::LsStatus st = sim->run([&](const generate::LsStatus& s) {
      log += fmt::format("{},{:.10g},{:.10g},{:.6g},{},{},{:.4f}\n", s.blocks, s.time, s.volume_fraction,
                         s.reduced_pressure, s.collisions, s.transfers, s.seconds);
      progress.update(s.blocks, fmt::format("phi {:.5f}, reduced pressure {:.3g}, {:.3g} collisions", s.volume_fraction,
                                            s.reduced_pressure, static_cast<double>(s.collisions)));
      checkpoint.write_if_due(save);  // between two blocks: a consistent state
    });
    checkpoint.write(save);
    progress.finish();
    const Packing packing = sim->packing();
    const std::string comment =
        fmt::format("packlab {} generate ls phi={:.8f} N={} growth_rate={:g} seed={} stop={}", io::version(),
                    packing.volume_fraction(), packing.size(), p.growth_rate, o.seed, generate::ls_stop_name(st.stop));
    const std::filesystem::path dir(run.out);
    write_packing_outputs(packing, dir, comment);
    io::write_text_atomically(dir / "ls_log.csv", log);
    io::PlotOptions po;
    po.enabled = !run.no_plots;
    io::make_plot("ls", {(dir / "ls_log.csv").string()}, dir / "ls.png", po);
    nlohmann::json report = io::report_header("generate ls");
    report["parameters"] = ls_parameters(o);
    report["results"] = {{"volume_fraction", packing.volume_fraction()},
                         {"stop", generate::ls_stop_name(st.stop)},
                         {"reduced_pressure", st.reduced_pressure},
                         {"collisions", st.collisions},
                         {"transfers", st.transfers},
                         {"stale_events", st.stale},
                         {"blocks", st.blocks},
                         {"simulated_time", st.time},
                         {"ls_seconds", st.seconds},
                         {"ls_cpu_seconds", st.cpu_seconds},
                         {"collisions_per_second", static_cast<double>(st.collisions) / st.seconds},
                         {"events_per_second", static_cast<double>(st.events()) / st.seconds},
                         {"collisions_per_cpu_second", static_cast<double>(st.collisions) / st.cpu_seconds},
                         {"events_per_cpu_second", static_cast<double>(st.events()) / st.cpu_seconds},
                         {"overlap_correction", sim->overlap_correction()},
                         {"min_contact_ratio", generate::min_contact_ratio(packing)}};
    report["results"]["rdf"] = rdf_of(packing, dir, run.rdf.dr, run.rdf.r_max, !run.no_plots);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    report["seconds"] = seconds;
    io::write_report(dir / "report.json", report);
    if (!run.quiet)
      fmt::print(
          "{}: phi {:.6f}, reduced pressure {:.3g}, {} collisions ({:.3g}/s, {:.3g} events/s); wrote {} in {:.2f} s\n",
          generate::ls_stop_name(st.stop), packing.volume_fraction(), st.reduced_pressure, st.collisions,
          static_cast<double>(st.collisions) / st.seconds, static_cast<double>(st.events()) / st.seconds, run.out,
          seconds);
    // One rule with generate fba: a target that was not reached is an error (exit 2), the
    // files of what was reached are kept for inspection.
    if (o.phi > 0.0 && st.stop != generate::LsStop::target_reached)
      fail_input(fmt::format("phi = {:g}: not reached, the run stopped ({}) at phi {:.4f} (files written to {}); "
                             "random close packing is near 0.64 for equal spheres",
                             o.phi, generate::ls_stop_name(st.stop), packing.volume_fraction(), run.out));
  });
}

}  // namespace packlab::cli
