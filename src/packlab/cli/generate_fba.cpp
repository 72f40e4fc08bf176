// packlab generate fba [--config FILE.toml] (--particles N [--aspect 1,1,1] | --box LX,LY,LZ) [--diameter D]
//   [--porosity 0.38] [--sizes 1,0.5 (--number-fractions ... | --volume-fractions ...)] [--periodic xy]
//   [--tolerance 1e-3] [--shrink-rate 0.01] [--momentum 0.9] [--step 1] [--max-iterations N] [--history-every K]
//   [--seed S]
//   [--threads T] [--checkpoint-seconds S] --out DIR
// packlab generate fba --resume DIR [--threads T]
// Force-biased algorithm (generate/fba.hpp, bpm-inverse-opals §2.1): dense random packing to a
// target porosity, periodic along the given axes (walls on the others). Writes DIR/packing.xyz,
// packing.vtu, fba_log.csv (convergence), fba.png, report.json and checkpoint.bin (every
// --checkpoint-seconds and at the end; --resume DIR goes on from it, cli/checkpoint.hpp). Exit
// code 2 (after writing the files) when the tolerance was not reached within --max-iterations.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>

#include "packlab/analyze/coordination.hpp"
#include "packlab/cli/checkpoint.hpp"
#include "packlab/cli/commands.hpp"
#include "packlab/cli/options.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/progress.hpp"
#include "packlab/generate/fba.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/options.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/plot.hpp"
#include "packlab/io/report.hpp"

namespace packlab::cli {

void add_generate_fba(CLI::App& generate) {
  add_option_command(
      generate, "fba",
      "Force-biased algorithm: dense random sphere packing to a target porosity (0.38 in bpm-inverse-opals)",
      io::fba_options, {.output = "Output folder", .plots = true, .resumable = true},
      [](OptionCommand<io::FbaOptions>& c) {
        const auto t0 = std::chrono::steady_clock::now();
        const io::FbaOptions& o = c.settings;
        const io::FbaOptions::Setup setup = o.setup();
        const Box& box = setup.box;
        const long n = setup.count;
        const generate::SizeClasses& classes = setup.classes;
        io::ensure_directory(c.out);
        std::optional<generate::FbaRun> fba;
        if (c.resumed) {
          fba.emplace(generate::FbaRun::load_state(c.resumed->state, o.fba.threads));
        } else {
          Random rng(o.seed);
          fba.emplace(box, generate::fba_class_radii(n, classes, rng), o.fba, rng, o.history_every);
        }
        Progress progress("generate fba", 0, !c.quiet);
        const auto on_progress = [&](const generate::FbaStatus& s) {
          progress.update(s.iteration, fmt::format("max overlap {:.3g}, nominal/target diameter {:.5f}", s.max_overlap,
                                                   s.outer_scale));
        };
        // Pieces of about 1e5 particle-iterations (milliseconds); a checkpoint may follow each
        // (a consistent state, between two iterations).
        const long chunk = std::max(1L, 100000L / n);
        CheckpointWriter checkpoint(c.out, c.flags->schema(), c.in, o.checkpoint_seconds);
        const auto save = [&](std::ostream& out) { fba->save_state(out); };
        while (!fba->run(chunk, on_progress)) checkpoint.write_if_due(save);
        checkpoint.write(save);
        progress.finish();
        const generate::FbaResult r = fba->result();
        const Packing& packing = r.packing;
        const std::filesystem::path dir(c.out);
        io::WriteOptions w;
        w.comment = fmt::format("packlab {} generate fba porosity={:g} N={} tolerance={:g} seed={} stop={}",
                                io::version(), o.fba.target_porosity, packing.size(), o.fba.tolerance, o.seed,
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
        po.enabled = !c.no_plots;
        io::make_plot("fba", {(dir / "fba_log.csv").string(), fmt::format("{:g}", o.fba.tolerance)}, dir / "fba.png",
                      po);
        analyze::Coordination cn(0.01);
        cn.compute(packing);
        const double diameter_max = 2.0 * *std::max_element(packing.radius.begin(), packing.radius.end());
        nlohmann::json report = io::report_header("generate fba");
        report["parameters"] = {{"particles", n},
                                {"box_m", {box.length.x, box.length.y, box.length.z}},
                                {"periodic", {box.periodic[0], box.periodic[1], box.periodic[2]}},
                                {"diameter_m", o.diameter},
                                {"sizes", classes.sizes},
                                {"number_fractions", classes.number_fractions()},
                                {"target_porosity", o.fba.target_porosity},
                                {"tolerance", o.fba.tolerance},
                                {"shrink_rate", o.fba.shrink_rate},
                                {"step", o.fba.step},
                                {"momentum", o.fba.momentum},
                                {"max_move", o.fba.max_move},
                                {"max_iterations", o.fba.max_iterations},
                                {"threads", o.fba.threads},
                                {"seed", o.seed}};
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
          fail_input(
              fmt::format("max_iterations = {}: the largest overlap is still {:.3g} > tolerance {:g} (files written "
                          "to {}); raise --max-iterations or --porosity",
                          o.fba.max_iterations, r.status.max_overlap, o.fba.tolerance, c.out));
        if (!c.quiet)
          fmt::print(
              "{}: {} spheres, porosity {:.6f}, max overlap {:.3g} (tolerance {:g}) after {} iterations "
              "({:.3g} s, {:.3g} particle-iterations/s); wrote {} in {:.2f} s\n",
              generate::fba_stop_name(r.status.stop), n, 1.0 - packing.volume_fraction(), r.verified_max_overlap,
              o.fba.tolerance, r.status.iteration, seconds_fba,
              seconds_fba > 0 ? static_cast<double>(r.status.iteration) * static_cast<double>(n) / seconds_fba : 0.0,
              c.out, seconds);
      });
}

}  // namespace packlab::cli
