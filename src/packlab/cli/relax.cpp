// packlab relax IN OUT [--config FILE.toml] [--contact-law L] [every material property as a flag:
//   --normal-stiffness, --shear-stiffness, --friction, --damping, --density, ...] [--stiffness-rule R]
//   [--time-step --time-step-safety --steps --tolerance --check-interval --threads --seed] [--log FILE.csv]
#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <sstream>

#include "packlab/cli/commands.hpp"
#include "packlab/cli/options.hpp"
#include "packlab/core/progress.hpp"
#include "packlab/dem/engine.hpp"
#include "packlab/dem/relax.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/options.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/plot.hpp"

namespace packlab::cli {

std::string relax_config_reference() {
  io::RelaxRun r;
  return io::relax_options(r).markdown();
}

void add_relax(CLI::App& app) {
  struct Options {
    std::string in, out, log;
    io::RelaxRun run;
    std::unique_ptr<OptionFlags> flags;
    bool quiet = false;
    bool no_plots = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "relax", "Relax a packing with a contact law and local damping until the forces balance");
  cmd->add_option("in", opt->in, "Input packing")->required();
  cmd->add_option("out", opt->out, "Output packing (format by extension)")->required();
  opt->flags = std::make_unique<OptionFlags>(cmd, io::relax_options(opt->run));
  cmd->add_option("--log", opt->log,
                  "Write the diagnostics of every check to this CSV file (and a plot beside it, .png)");
  cmd->add_flag("--no-plots", opt->no_plots, "Do not draw the PNG plot of the log");
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->callback([opt] {
    const auto t0 = std::chrono::steady_clock::now();
    opt->flags->load();
    const Packing packing = io::read_packing(opt->in);
    // Check the output path before running (no surprise after a long run).
    (void)io::format_from_path(opt->out);
    const dem::EngineConfig config = opt->run.config();
    const dem::Material& material = config.types.front();
    dem::Engine engine(packing, config);
    Progress progress("relax", opt->run.relax.max_steps, !opt->quiet);
    dem::RelaxOptions ro = opt->run.relax;
    ro.on_check = [&](const dem::Diagnostics& d) {
      progress.update(d.step, fmt::format("unbalanced {:.3g}, CN {:.3f}", d.unbalanced_force_ratio,
                                          d.mean_coordination));
    };
    const dem::RelaxResult result = dem::relax(engine, ro);
    progress.finish();
    io::WriteOptions w;
    w.comment = fmt::format("packlab relax {} steps={} kn={:g} ks={:g} mu={:g} damping={:g} dt={:.6g}", opt->in,
                            result.steps, material.normal_stiffness, material.shear_stiffness, material.friction,
                            material.damping, engine.time_step());
    io::write_packing(engine.packing(), opt->out, w);
    if (!opt->log.empty()) {
      std::ostringstream csv;
      csv << "step,time,kinetic_energy,strain_energy,unbalanced_force_ratio,mean_coordination,contacts\n";
      for (const auto& d : result.history)
        csv << fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{}\n", d.step, d.time, d.kinetic_energy,
                           d.strain_energy, d.unbalanced_force_ratio, d.mean_coordination, d.contacts);
      io::write_text_atomically(opt->log, csv.str());
      io::PlotOptions plot;
      plot.enabled = !opt->no_plots;
      io::make_plot("relax", {opt->log}, std::filesystem::path(opt->log).replace_extension(".png"), plot);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!opt->quiet) {
      fmt::print("{}\n", result.reason());
      fmt::print("time step {:.6g} s, mean coordination {:.4f}, kinetic energy {:.4g} J, strain energy {:.4g} J\n",
                 engine.time_step(), result.last.mean_coordination, result.last.kinetic_energy,
                 result.last.strain_energy);
      fmt::print("wrote {} in {:.2f} s ({:.3g} particle-steps/s)\n", opt->out, seconds,
                 static_cast<double>(engine.particle_count()) * static_cast<double>(result.steps) / seconds);
    }
  });
}

}  // namespace packlab::cli
