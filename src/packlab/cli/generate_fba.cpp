// packlab generate fba (--particles N [--aspect 1,1,1] | --box LX,LY,LZ) [--diameter D] [--porosity 0.38]
//   [--sizes 1,0.5 (--number-fractions ... | --volume-fractions ...)] [--periodic xy] [--tolerance 1e-3]
//   [--shrink-rate 0.01] [--step 1] [--max-iterations N] [--seed S] [--threads T] --out DIR
// Force-biased algorithm (generate/fba.hpp, bpm-inverse-opals §2.1): dense random packing to a
// target porosity, periodic along the given axes (walls on the others). Writes DIR/packing.xyz,
// packing.vtu, fba_log.csv (convergence), fba.png and report.json. Exit code 2 (after writing
// the files) when the tolerance was not reached within --max-iterations.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>

#include "packlab/analyze/coordination.hpp"
#include "packlab/cli/commands.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/progress.hpp"
#include "packlab/generate/fba.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/plot.hpp"
#include "packlab/io/report.hpp"

namespace packlab::cli {

void add_generate_fba(CLI::App& generate) {
  struct Options {
    long particles = 0;
    std::vector<double> box, aspect{1, 1, 1};
    double diameter = 1.0;
    std::vector<double> sizes{1.0}, number_fractions, volume_fractions;
    std::string periodic = "xyz";
    generate::FbaParams fba;
    std::uint64_t seed = 1;
    std::string out;
    bool quiet = false, no_plots = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = generate.add_subcommand(
      "fba", "Force-biased algorithm: dense random sphere packing to a target porosity (0.38 in bpm-inverse-opals)");
  cmd->add_option("--particles", opt->particles, "Number of spheres (the box follows from --diameter and --aspect)");
  cmd->add_option("--box", opt->box, "Box edges LX,LY,LZ [m] (the number of spheres follows from --diameter)")
      ->delimiter(',')
      ->expected(3);
  cmd->add_option("--aspect", opt->aspect, "Box edge ratios with --particles")->delimiter(',')->expected(3);
  cmd->add_option("--diameter", opt->diameter, "Diameter of the largest size class [m]")->capture_default_str();
  cmd->add_option("--porosity", opt->fba.target_porosity, "Target porosity 1 - sum V_i / V_box, in [0.30, 1)")
      ->capture_default_str();
  cmd->add_option("--sizes", opt->sizes, "Relative diameters of the size classes, e.g. 1,0.5")->delimiter(',');
  cmd->add_option("--number-fractions", opt->number_fractions, "Number fractions of the classes (normalized)")
      ->delimiter(',');
  cmd->add_option("--volume-fractions", opt->volume_fractions, "Volume fractions of the classes (normalized)")
      ->delimiter(',');
  cmd->add_option("--periodic", opt->periodic, "Periodic axes (subset of xyz, or none); walls on the others")
      ->capture_default_str();
  cmd->add_option("--tolerance", opt->fba.tolerance,
                  "Stop when the largest overlap (r_i + r_j - d)/(r_i + r_j) is at most this, in (0, 0.1]")
      ->capture_default_str();
  cmd->add_option("--shrink-rate", opt->fba.shrink_rate,
                  "Fraction of the gap between nominal and true diameter removed per iteration, in (0, 1]")
      ->capture_default_str();
  cmd->add_option("--step", opt->fba.step, "Fraction of each pair's overlap removed per iteration, in (0, 1]")
      ->capture_default_str();
  cmd->add_option("--max-iterations", opt->fba.max_iterations, "Iteration limit")->capture_default_str();
  cmd->add_option("--seed", opt->seed, "Random seed")->capture_default_str();
  cmd->add_option("--threads", opt->fba.threads, "Threads of the neighbour search")->capture_default_str();
  cmd->add_option("--out", opt->out, "Output folder")->required();
  cmd->add_flag("--no-plots", opt->no_plots, "Do not write PNG plots");
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->callback([opt] {
    const auto t0 = std::chrono::steady_clock::now();
    const generate::SizeClasses classes =
        generate::SizeClasses::from_options(opt->sizes, opt->number_fractions, opt->volume_fractions);
    opt->fba.validate();
    require(opt->diameter > 0.0 && std::isfinite(opt->diameter), "diameter", opt->diameter, "> 0 m");
    if ((opt->particles > 0) == !opt->box.empty())
      fail_input("--particles and --box: give exactly one of them");
    Box box;
    box.periodic = generate::periodic_axes_from_name(opt->periodic);
    const double smax = *std::max_element(classes.sizes.begin(), classes.sizes.end());
    long n = opt->particles;
    if (!opt->box.empty()) {
      for (int a = 0; a < 3; ++a)
        require(opt->box[static_cast<std::size_t>(a)] > 0.0, "box", opt->box[static_cast<std::size_t>(a)], "> 0 m");
      box.length = {opt->box[0], opt->box[1], opt->box[2]};
      n = generate::fba_count_for_volume(box.volume(), opt->fba.target_porosity, opt->diameter, classes);
    } else {
      require(n >= 2 && n <= 100'000'000, "particles", static_cast<double>(n), "in [2, 1e8]");
      for (double a : opt->aspect) require(a > 0.0, "aspect", a, "> 0");
      const std::vector<double> x = classes.number_fractions();
      double mean_volume = 0;
      for (std::size_t k = 0; k < x.size(); ++k)
        mean_volume += x[k] * std::numbers::pi / 6.0 * std::pow(classes.sizes[k] / smax * opt->diameter, 3);
      const double volume = static_cast<double>(n) * mean_volume / (1.0 - opt->fba.target_porosity);
      const double s = std::cbrt(volume / (opt->aspect[0] * opt->aspect[1] * opt->aspect[2]));
      box.length = {opt->aspect[0] * s, opt->aspect[1] * s, opt->aspect[2] * s};
    }
    io::ensure_directory(opt->out);
    Random rng(opt->seed);
    std::vector<double> rho = generate::fba_class_radii(n, classes, rng);
    Progress progress("generate fba", 0, !opt->quiet);
    const generate::FbaResult r =
        generate::fba_pack(box, rho, opt->fba, rng, 10, [&](const generate::FbaStatus& s) {
          progress.update(s.iteration, fmt::format("max overlap {:.3g}, nominal/target diameter {:.5f}",
                                                   s.max_overlap, s.outer_scale));
        });
    progress.finish();
    const Packing& packing = r.packing;
    const std::filesystem::path dir(opt->out);
    io::WriteOptions w;
    w.comment = fmt::format("packlab {} generate fba porosity={:g} N={} tolerance={:g} seed={} stop={}",
                            io::version(), opt->fba.target_porosity, packing.size(), opt->fba.tolerance, opt->seed,
                            generate::fba_stop_name(r.status.stop));
    io::write_packing(packing, dir / "packing.xyz", w);
    io::write_packing(packing, dir / "packing.vtu", w);
    std::ostringstream log;
    log << "iteration,outer_scale,inner_scale,max_overlap,overlapping_pairs,seconds\n";
    for (const auto& s : r.history)
      log << fmt::format("{},{:.10g},{:.10g},{:.6g},{},{:.4f}\n", s.iteration, s.outer_scale, s.inner_scale,
                         s.max_overlap, s.overlapping_pairs, s.seconds);
    io::write_text_atomically(dir / "fba_log.csv", log.str());
    io::PlotOptions po;
    po.enabled = !opt->no_plots;
    io::make_plot("fba", {(dir / "fba_log.csv").string(), fmt::format("{:g}", opt->fba.tolerance)},
                  dir / "fba.png", po);
    analyze::Coordination cn(0.01);
    cn.compute(packing);
    const double diameter_max = 2.0 * *std::max_element(packing.radius.begin(), packing.radius.end());
    nlohmann::json report = io::report_header("generate fba");
    report["parameters"] = {{"particles", n},
                            {"box_m", {box.length.x, box.length.y, box.length.z}},
                            {"periodic", {box.periodic[0], box.periodic[1], box.periodic[2]}},
                            {"diameter_m", opt->diameter},
                            {"sizes", classes.sizes},
                            {"number_fractions", classes.number_fractions()},
                            {"target_porosity", opt->fba.target_porosity},
                            {"tolerance", opt->fba.tolerance},
                            {"shrink_rate", opt->fba.shrink_rate},
                            {"step", opt->fba.step},
                            {"max_move", opt->fba.max_move},
                            {"max_iterations", opt->fba.max_iterations},
                            {"threads", opt->fba.threads},
                            {"seed", opt->seed}};
    const double seconds_fba = r.status.seconds;
    report["results"] = {
        {"stop", generate::fba_stop_name(r.status.stop)},
        {"porosity", 1.0 - packing.volume_fraction()},
        {"volume_fraction", packing.volume_fraction()},
        {"iterations", r.status.iteration},
        {"max_overlap", r.status.max_overlap},
        {"verified_max_overlap", r.verified_max_overlap},
        {"largest_diameter_m", diameter_max},
        {"mean_coordination_eps_0.01", cn.mean()},
        {"fba_seconds", seconds_fba},
        {"iterations_per_second", seconds_fba > 0 ? static_cast<double>(r.status.iteration) / seconds_fba : 0.0},
        {"particle_iterations_per_second",
         seconds_fba > 0 ? static_cast<double>(r.status.iteration) * static_cast<double>(n) / seconds_fba : 0.0}};
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    report["seconds"] = seconds;
    io::write_report(dir / "report.json", report);
    if (r.status.stop != generate::FbaStop::target_reached)
      fail_input(fmt::format("max_iterations = {}: the largest overlap is still {:.3g} > tolerance {:g} (files written "
                             "to {}); raise --max-iterations or --porosity",
                             opt->fba.max_iterations, r.status.max_overlap, opt->fba.tolerance, opt->out));
    if (!opt->quiet)
      fmt::print("{}: {} spheres, porosity {:.6f}, max overlap {:.3g} (tolerance {:g}) after {} iterations "
                 "({:.3g} s, {:.3g} particle-iterations/s); wrote {} in {:.2f} s\n",
                 generate::fba_stop_name(r.status.stop), n, 1.0 - packing.volume_fraction(), r.verified_max_overlap,
                 opt->fba.tolerance, r.status.iteration, seconds_fba,
                 seconds_fba > 0 ? static_cast<double>(r.status.iteration) * static_cast<double>(n) / seconds_fba : 0.0,
                 opt->out, seconds);
  });
}

}  // namespace packlab::cli
