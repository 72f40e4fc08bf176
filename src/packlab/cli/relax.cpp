// packlab relax IN OUT [--config FILE.toml] [--contact-law L] [every material property as a flag:
//   --normal-stiffness, --shear-stiffness, --friction, --damping, --density, ...] [--stiffness-rule R]
//   [--time-step --time-step-safety --steps --tolerance --check-interval --threads --seed] [--log FILE.csv]
//   [--checkpoint DIR [--checkpoint-seconds S]]
// packlab relax --resume DIR [--threads T] [--adapt-threads=false]
// With --checkpoint DIR the engine's and the relaxation's state go to DIR/checkpoint.bin every
// --checkpoint-seconds and at the end (cli/checkpoint.hpp); --resume DIR goes on from it and
// writes OUT (and the log) as the uninterrupted run would have, bit for bit.
#include "packlab/dem/relax.hpp"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <sstream>

#include "packlab/cli/checkpoint.hpp"
#include "packlab/cli/commands.hpp"
#include "packlab/cli/options.hpp"
#include "packlab/core/binary_io.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/progress.hpp"
#include "packlab/dem/engine.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/options.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/plot.hpp"

namespace packlab::cli {

void add_relax(CLI::App& app) {
  auto log = std::make_shared<std::string>();
  auto checkpoint_dir = std::make_shared<std::string>();
  // The material keys are those of every law; the engine checks the ones its law reads.
  CLI::App* cmd = add_option_command(
      app, "relax", "Relax a packing with a contact law and local damping until the forces balance", io::relax_options,
      {.input = "Input packing",
       .output = "Output packing (format by extension)",
       .output_positional = true,
       .plots = true,
       .validate = false,
       .resumable = true},
      [log, checkpoint_dir](OptionCommand<io::RelaxRun>& c) {
        const auto t0 = std::chrono::steady_clock::now();
        // The output file, the log and the checkpoint folder: given, or those of the saved run.
        std::string out = c.out, log_path = *log, dir = *checkpoint_dir;
        if (c.resumed) {
          if (!log->empty() || !dir.empty())
            fail_input(fmt::format("{} cannot be combined with --resume: the run continues with its saved settings",
                                   log->empty() ? "--checkpoint" : "--log"));
          binary::read_string(c.resumed->state, out, "output file");
          binary::read_string(c.resumed->state, log_path, "log file");
          dir = c.resume;
        }
        const Packing packing = io::read_packing(c.in);
        // Check the output paths before running (no surprise after a long run).
        (void)io::format_from_path(out);
        io::check_writable_file(out);
        if (!log_path.empty()) io::check_writable_file(log_path);
        if (!dir.empty()) io::ensure_directory(dir);
        const dem::EngineConfig config = c.settings.config();
        const dem::Material& material = config.types.front();
        dem::Engine engine(packing, config);
        Progress progress("relax", c.settings.relax.max_steps, !c.quiet);
        dem::RelaxOptions ro = c.settings.relax;
        ro.on_check = [&](const dem::Diagnostics& d) {
          progress.update(d.step,
                          fmt::format("unbalanced {:.3g}, CN {:.3f}", d.unbalanced_force_ratio, d.mean_coordination));
        };
        CheckpointWriter checkpoint(dir, c.flags->schema(), c.in, c.settings.checkpoint_seconds);
        if (!dir.empty())
          ro.checkpoint = [&](const std::function<void(std::ostream&)>& state, bool end) {
            const auto write = [&](std::ostream& o) {
              binary::write_string(o, out);
              binary::write_string(o, log_path);
              state(o);
            };
            end ? checkpoint.write(write) : checkpoint.write_if_due(write);
          };
        if (c.resumed) ro.resume = &c.resumed->state;
        const dem::RelaxResult result = dem::relax(engine, ro);
        progress.finish();
        io::WriteOptions w;
        w.comment = fmt::format("packlab relax {} steps={} kn={:g} ks={:g} mu={:g} damping={:g} dt={:.6g}", c.in,
                                result.steps, material.normal_stiffness, material.shear_stiffness, material.friction,
                                material.damping, engine.time_step());
        io::write_packing(engine.packing(), out, w);
        if (!log_path.empty()) {
          std::ostringstream csv;
          csv << "step,time,kinetic_energy,strain_energy,unbalanced_force_ratio,mean_coordination,contacts\n";
          for (const auto& d : result.history)
            csv << fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{}\n", d.step, d.time, d.kinetic_energy,
                               d.strain_energy, d.unbalanced_force_ratio, d.mean_coordination, d.contacts);
          io::write_text_atomically(log_path, csv.str());
          io::PlotOptions plot;
          plot.enabled = !c.no_plots;
          io::make_plot("relax", {log_path}, std::filesystem::path(log_path).replace_extension(".png"), plot);
        }
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (!c.quiet) {
          fmt::print("{}\n", result.reason());
          fmt::print("time step {:.6g} s, mean coordination {:.4f}, kinetic energy {:.4g} J, strain energy {:.4g} J\n",
                     engine.time_step(), result.last.mean_coordination, result.last.kinetic_energy,
                     result.last.strain_energy);
          fmt::print("wrote {} in {:.2f} s ({:.3g} particle-steps/s)\n", out, seconds,
                     static_cast<double>(engine.particle_count()) * static_cast<double>(result.steps) / seconds);
        }
      });
  cmd->add_option("--log", *log, "Write the diagnostics of every check to this CSV file (and a plot beside it, .png)");
  cmd->add_option("--checkpoint", *checkpoint_dir,
                  "Write a checkpoint into this folder every --checkpoint-seconds and at the end; `packlab relax "
                  "--resume DIR` continues an interrupted run");
}

}  // namespace packlab::cli
