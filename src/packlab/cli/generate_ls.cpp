// packlab generate ls [--phi X] --particles N [--sizes 1,0.313 (--number-fractions ... | --volume-fractions ...)]
//   [--radius R] [--growth-rate G] [--max-pressure P] [--events-per-block E] [--seed S] --out DIR
// Lubachevsky-Stillinger growth from random points to the volume fraction X, or to jamming
// without --phi. Writes DIR/packing.xyz, .vtu, ls_log.csv, rdf.csv (+ rdf_partial.csv),
// windows.csv, PNG plots and report.json.
#include <fmt/format.h>

#include <chrono>
#include <memory>
#include <sstream>

#include "packlab/cli/commands.hpp"
#include "packlab/cli/scrm_common.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/progress.hpp"
#include "packlab/generate/ls.hpp"
#include "packlab/generate/overlap_check.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/plot.hpp"
#include "packlab/io/report.hpp"

namespace packlab::cli {

generate::SizeClasses LsRunOptions::classes() const {
  return generate::SizeClasses::from_options(sizes, number_fractions, volume_fractions);
}

nlohmann::json LsRunOptions::parameters() const {
  const generate::SizeClasses c = classes();
  return {{"phi", phi},
          {"particles", particles},
          {"sizes", sizes},
          {"number_fractions", c.number_fractions()},
          {"counts", c.counts(particles)},
          {"radius_m", radius},
          {"growth_rate", ls.growth_rate},
          {"max_reduced_pressure", ls.max_reduced_pressure},
          {"events_per_block", ls.events_per_block},
          {"separation_boost", ls.separation_boost},
          {"seed", seed}};
}

void add_ls_options(CLI::App& cmd, LsRunOptions& o) {
  cmd.add_option("--phi", o.phi, "Target volume fraction; omitted: grow until jammed")->capture_default_str();
  cmd.add_option("--particles", o.particles, "Number of spheres")->capture_default_str();
  cmd.add_option("--sizes", o.sizes, "Relative diameters of the size classes, e.g. 1,0.313")->delimiter(',');
  cmd.add_option("--number-fractions", o.number_fractions, "Number fractions of the classes (normalized)")
      ->delimiter(',');
  cmd.add_option("--volume-fractions", o.volume_fractions, "Volume fractions of the classes (normalized)")
      ->delimiter(',');
  cmd.add_option("--radius", o.radius,
                 "Radius of the largest class at the target volume fraction (0.64 when growing to jamming) [m]")
      ->capture_default_str();
  cmd.add_option("--growth-rate", o.ls.growth_rate,
                 "G = ds/dt: growth of the largest diameter per unit time, in units of its box-filling size "
                 "and of the thermal speed")
      ->capture_default_str();
  cmd.add_option("--max-pressure", o.ls.max_reduced_pressure, "Jamming criterion: reduced pressure PV/NkT")
      ->capture_default_str();
  cmd.add_option("--events-per-block", o.ls.events_per_block,
                 "Events per particle between velocity rescalings and pressure measurements")
      ->capture_default_str();
  cmd.add_option("--seed", o.seed, "Random seed")->capture_default_str();
  cmd.add_option("--rdf-dr", o.rdf_dr, "RDF bin width in units of the largest radius")->capture_default_str();
  cmd.add_option("--rdf-rmax", o.rdf_rmax, "RDF range in units of the largest radius")->capture_default_str();
  cmd.add_option("--out", o.out, "Output folder")->required();
  cmd.add_flag("--no-plots", o.no_plots, "Do not write PNG plots");
  cmd.add_flag("--quiet", o.quiet, "No progress output");
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

void add_generate_ls(CLI::App& generate) {
  auto opt = std::make_shared<LsRunOptions>();
  auto* cmd = generate.add_subcommand(
      "ls", "Lubachevsky-Stillinger growth of hard spheres (event-driven MD) to a volume fraction or to jamming");
  add_ls_options(*cmd, *opt);
  cmd->callback([opt] {
    const auto t0 = std::chrono::steady_clock::now();
    const generate::SizeClasses classes = opt->classes();
    generate::LsParams p = opt->ls;
    p.target_volume_fraction = opt->phi;
    p.validate();
    {
      analyze::RdfParams rp;
      rp.dr = opt->rdf_dr;
      rp.r_max = opt->rdf_rmax;
      rp.validate();
    }
    io::ensure_directory(opt->out);
    Random rng(opt->seed);
    const generate::LsStart start =
        generate::make_ls_start(opt->particles, classes, opt->radius, opt->phi > 0 ? opt->phi : 0.64, rng);
    generate::LsSimulation sim(start.box, start.points, start.unit_radius, p, rng);
    Progress progress("generate ls", 0, !opt->quiet);
    std::ostringstream log;
    log << "block,time,volume_fraction,reduced_pressure,collisions,transfers,seconds\n";
    const generate::LsStatus st = sim.run([&](const generate::LsStatus& s) {
      log << fmt::format("{},{:.10g},{:.10g},{:.6g},{},{},{:.4f}\n", s.blocks, s.time, s.volume_fraction,
                         s.reduced_pressure, s.collisions, s.transfers, s.seconds);
      progress.update(s.blocks, fmt::format("phi {:.5f}, reduced pressure {:.3g}, {:.3g} collisions", s.volume_fraction,
                                            s.reduced_pressure, static_cast<double>(s.collisions)));
    });
    progress.finish();
    const Packing packing = sim.packing();
    const std::string comment =
        fmt::format("packlab {} generate ls phi={:.8f} N={} growth_rate={:g} seed={} stop={}", io::version(),
                    packing.volume_fraction(), packing.size(), p.growth_rate, opt->seed, generate::ls_stop_name(st.stop));
    const std::filesystem::path dir(opt->out);
    write_packing_outputs(packing, dir, comment);
    io::write_text_atomically(dir / "ls_log.csv", log.str());
    io::PlotOptions po;
    po.enabled = !opt->no_plots;
    io::make_plot("ls", {(dir / "ls_log.csv").string()}, dir / "ls.png", po);
    nlohmann::json report = io::report_header("generate ls");
    report["parameters"] = opt->parameters();
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
                         {"overlap_correction", sim.overlap_correction()},
                         {"min_contact_ratio", generate::min_contact_ratio(packing)}};
    report["results"]["rdf"] = rdf_of(packing, dir, opt->rdf_dr, opt->rdf_rmax, !opt->no_plots);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    report["seconds"] = seconds;
    io::write_report(dir / "report.json", report);
    if (!opt->quiet)
      fmt::print("{}: phi {:.6f}, reduced pressure {:.3g}, {} collisions ({:.3g}/s, {:.3g} events/s); wrote {} in {:.2f} s\n",
                 generate::ls_stop_name(st.stop), packing.volume_fraction(), st.reduced_pressure, st.collisions,
                 static_cast<double>(st.collisions) / st.seconds, static_cast<double>(st.events()) / st.seconds,
                 opt->out, seconds);
  });
}

}  // namespace packlab::cli
