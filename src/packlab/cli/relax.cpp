// packlab relax IN OUT [--normal-stiffness --shear-stiffness --friction --damping --density
//   --time-step --steps --tolerance --threads --seed --stiffness-rule --log FILE.csv]
#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <sstream>

#include "packlab/cli/commands.hpp"
#include "packlab/core/progress.hpp"
#include "packlab/dem/engine.hpp"
#include "packlab/dem/relax.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/plot.hpp"

namespace packlab::cli {

void add_relax(CLI::App& app) {
  struct Options {
    std::string in, out, log;
    dem::Material material;
    std::string stiffness_rule = "particle";
    double time_step = 0.0;
    double time_step_safety = 0.2;
    long steps = 100000;
    double tolerance = 1e-3;
    long check_interval = 100;
    int threads = 0;
    std::uint64_t seed = 1;
    bool quiet = false;
    bool no_plots = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "relax", "Relax a packing with the linear contact law and local damping until the forces balance");
  cmd->add_option("in", opt->in, "Input packing")->required();
  cmd->add_option("out", opt->out, "Output packing (format by extension)")->required();
  cmd->add_option("--normal-stiffness", opt->material.normal_stiffness, "Normal stiffness k_n [N/m]")
      ->capture_default_str();
  cmd->add_option("--shear-stiffness", opt->material.shear_stiffness, "Shear stiffness k_s [N/m]")
      ->capture_default_str();
  cmd->add_option("--friction", opt->material.friction, "Coulomb friction coefficient [-]")->capture_default_str();
  cmd->add_option("--damping", opt->material.damping, "Local damping coefficient alpha in [0, 1)")
      ->capture_default_str();
  cmd->add_option("--density", opt->material.density,
                  "Particle density [kg/m^3], used when the file has none (LAMMPS data files do)")
      ->capture_default_str();
  cmd->add_option("--stiffness-rule", opt->stiffness_rule,
                  "particle: stiffnesses are PFC particle stiffnesses in series (contact = k/2); "
                  "contact: they are contact stiffnesses (LAMMPS kn)")
      ->capture_default_str();
  cmd->add_option("--time-step", opt->time_step, "Time step [s]; 0 = safety * min sqrt(m/k)")
      ->capture_default_str();
  cmd->add_option("--time-step-safety", opt->time_step_safety, "Safety factor of the automatic time step")
      ->capture_default_str();
  cmd->add_option("--steps", opt->steps, "Step limit")->capture_default_str();
  cmd->add_option("--tolerance", opt->tolerance,
                  "Stop when the mean unbalanced force ratio falls below this; 0 runs exactly --steps steps")
      ->capture_default_str();
  cmd->add_option("--check-interval", opt->check_interval, "Steps between diagnostics")->capture_default_str();
  cmd->add_option("--threads", opt->threads, "OpenMP threads (0 = all cores)")->capture_default_str();
  cmd->add_option("--seed", opt->seed, "Accepted for uniformity; relax draws no random numbers")
      ->capture_default_str();
  cmd->add_option("--log", opt->log,
                  "Write the diagnostics of every check to this CSV file (and a plot beside it, .png)");
  cmd->add_flag("--no-plots", opt->no_plots, "Do not draw the PNG plot of the log");
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->callback([opt] {
    const auto t0 = std::chrono::steady_clock::now();
    const Packing packing = io::read_packing(opt->in);
    // Check the output path before running (no surprise after a long run).
    (void)io::format_from_path(opt->out);
    dem::EngineConfig config;
    config.types = {opt->material};
    config.stiffness_rule = dem::stiffness_rule_from_name(opt->stiffness_rule);
    config.time_step = opt->time_step;
    config.time_step_safety = opt->time_step_safety;
    config.threads = opt->threads;
    dem::Engine engine(packing, config);
    Progress progress("relax", opt->steps, !opt->quiet);
    dem::RelaxOptions ro;
    ro.max_steps = opt->steps;
    ro.tolerance = opt->tolerance;
    ro.check_interval = opt->check_interval;
    ro.on_check = [&](const dem::Diagnostics& d) {
      progress.update(d.step, fmt::format("unbalanced {:.3g}, CN {:.3f}", d.unbalanced_force_ratio,
                                          d.mean_coordination));
    };
    const dem::RelaxResult result = dem::relax(engine, ro);
    progress.finish();
    io::WriteOptions w;
    w.comment = fmt::format("packlab relax {} steps={} kn={:g} ks={:g} mu={:g} damping={:g} dt={:.6g}", opt->in,
                            result.steps, opt->material.normal_stiffness, opt->material.shear_stiffness,
                            opt->material.friction, opt->material.damping, engine.time_step());
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
