// packlab generate vem [--config FILE.toml] [--structural N] [--voids N] [--phi-s X] [--radius R]
//   [--seed S] [--threads T] [--max-q Q] [--snapshot-every K] [--checkpoint-seconds S] [any option
//   of io::vem_options() as --key-with-dashes] [--no-plots] [--quiet] --out DIR
// packlab generate vem --resume DIR [--threads T] [--adapt-threads=false]
//
// The void expansion method (generate/vem.hpp, docs/vem.md). DIR receives packing.xyz and
// packing.vtu (the structural particles at the end, voids removed), cn_curve.csv, cn_curve.png,
// report.json (inflection point, beta, parameters, timings), checkpoint.bin (written every
// --checkpoint-seconds and at the end) and, with --snapshot-every K, snapshots/cycle_NNNNN.xyz
// (structural particles before every K-th increment). Flags override the config file.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "packlab/analyze/inflection.hpp"
#include "packlab/analyze/power_law.hpp"
#include "packlab/cli/commands.hpp"
#include "packlab/cli/options.hpp"
#include "packlab/core/binary_io.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/progress.hpp"
#include "packlab/generate/vem.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/config.hpp"
#include "packlab/io/options.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/plot.hpp"
#include "packlab/io/report.hpp"

namespace packlab::cli {

namespace {

// Settings of the command (not of the method); saved after the method's state in checkpoint.bin.
struct RunSettings {
  long snapshot_every = 0;            // 0 = no snapshots
  double checkpoint_seconds = 120;    // wall-clock seconds between checkpoints
  double window_widths = 4.0;         // inflection fit window, in logistic widths
  double power_law_max_excess = 1.0;  // largest Phi_T - Phi_T,i in the beta fit
  bool plots = true;
};

constexpr std::uint64_t settings_magic = 0x31544553434D4556ULL;  // "VEMCSET1"

// The command's own settings: output and the analysis of the curve (not keywords of
// packlab.generate_vem, which returns the curve for find_inflection()).
io::ConfigSchema run_settings_options(RunSettings& s) {
  io::ConfigSchema schema("generate vem");
  schema
      .integer("output.snapshot_every", s.snapshot_every,
               "Save the structural packing before every k-th increment (0 = never)")
      .range(ranges::non_negative)
      .alias("snapshot_every")
      .command_only();
  io::add_checkpoint_seconds(schema, s.checkpoint_seconds);
  schema.boolean("output.plots", s.plots, "Draw cn_curve.png")
      .command_only()
      .number("analysis.window_widths", s.window_widths, "Inflection fit window, in logistic widths")
      .range(ranges::positive)
      .command_only()
      .number("analysis.power_law_max_excess", s.power_law_max_excess,
              "Largest Phi_T - Phi_T,i in the beta fit of eq. 9")
      .range(ranges::positive)
      .command_only();
  return schema;
}

// Every key of the config file and every flag, bound to the parameters it sets
// (docs/config-reference.md is generated from this). Unknown keys are errors.
io::ConfigSchema vem_schema(generate::VemParams& p, RunSettings& s) {
  return io::vem_options(p).append(run_settings_options(s));
}

}  // namespace

std::string vem_config_reference() {
  generate::VemParams p;
  RunSettings s;
  return vem_schema(p, s).markdown();
}

namespace {

void write_checkpoint(const std::filesystem::path& dir, const generate::Vem& vem, const RunSettings& s) {
  io::write_atomically(dir / "checkpoint.bin", [&](std::ostream& out) {
    vem.save_checkpoint(out);
    binary::write(out, settings_magic);
    binary::write(out, s.snapshot_every);
    binary::write(out, s.checkpoint_seconds);
    binary::write(out, s.window_widths);
    binary::write(out, s.power_law_max_excess);
    binary::write(out, static_cast<std::uint8_t>(s.plots));
  });
}

std::string curve_csv(const generate::Vem& vem) {
  const auto& p = vem.params();
  std::string csv = fmt::format(
      "# packlab {} generate vem: N_S={} N_V={} phi_s={:.17g} r_S={:.17g} m seed={}\n"
      "# q = r_V/r_S; cn = mean coordination of structural particles, contact distance (1+{:g}) 2 r_S; "
      "phi_total = phi_s (1 + q^3 n) (eq. 5); energies in J (kinetic with scaled void masses); "
      "steps = relaxation steps that led to the row\n"
      "q,cn,phi_total,strain_energy,kinetic_energy,steps,cycle,unbalanced_force_ratio,converged\n",
      io::version(), p.structural, p.voids, p.phi_s, p.radius, p.seed, p.contact_eps);
  for (const auto& r : vem.curve())
    csv +=
        fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{},{},{:.6g},{}\n", r.q, r.cn, r.phi_total,
                    r.strain_energy, r.kinetic_energy, r.steps, r.cycle, r.unbalanced_force_ratio, r.converged ? 1 : 0);
  return csv;
}

nlohmann::json params_json(generate::VemParams p) {
  nlohmann::json out = io::vem_options(p).json();
  out["stiffness_rule"] = "particle";
  out["contact_law"] = "linear";
  out["relax"]["criterion"] =
      "unbalanced force ratio of the touching particles < tolerance, or max overlap/(r_i+r_j) < overlap";
  return out;
}

nlohmann::json finish(const std::filesystem::path& dir, const generate::Vem& vem, const RunSettings& s, bool quiet) {
  const auto& p = vem.params();
  const Packing structural = vem.structural_packing();
  io::WriteOptions w;
  w.comment =
      fmt::format("packlab {} generate vem N_S={} N_V={} phi_s={:.17g} r_S={:.17g} seed={} q_end={:.6g}", io::version(),
                  p.structural, p.voids, p.phi_s, p.radius, p.seed, vem.curve().empty() ? 0.0 : vem.curve().back().q);
  io::write_packing(structural, dir / "packing.xyz", w);
  io::write_packing(structural, dir / "packing.vtu", w);
  io::write_text_atomically(dir / "cn_curve.csv", curve_csv(vem));

  std::vector<double> q, cn, phi;
  for (const auto& r : vem.curve()) {
    q.push_back(r.q);
    cn.push_back(r.cn);
    phi.push_back(r.phi_total);
  }
  const double n = p.number_ratio();
  const double n13 = std::cbrt(n);
  nlohmann::json report = io::report_header("generate vem");
  analyze::InflectionOptions io_opt;
  io_opt.window_widths = s.window_widths;
  const analyze::Inflection inf = analyze::find_inflection(q, cn, io_opt);
  std::vector<std::string> plot_args{(dir / "cn_curve.csv").string()};
  if (inf.found) {
    const auto phi_i = analyze::inflection_volume_fraction(p.phi_s, n, inf);
    report["inflection"] = {
        {"q", inf.x},
        {"cn", inf.y},
        {"slope", inf.slope},
        {"phi_total", phi_i.value},
        {"q_err", inf.x_err},
        {"cn_err", inf.y_err},
        {"slope_err", inf.slope_err},
        {"phi_total_err", phi_i.err},
        {"q_window", inf.x_window},
        {"cn_window", inf.y_window},
        {"slope_window", inf.slope_window},
        {"width", inf.width},
        {"fit_window", {inf.x_lo, inf.x_hi}},
        {"points", inf.points},
        {"r2", inf.r2},
        {"q_n13", inf.x * n13},
        {"slope_n13", inf.slope * n13},
        {"method",
         "logistic step on a linear baseline, Levenberg-Marquardt, refitted on |q - q_i| <= window_widths * w; "
         "*_err: standard errors from the covariance; *_window: change with a 0.75x/1.25x window"}};
    const analyze::PowerLaw pl =
        analyze::fit_power_law(phi, cn, phi_i.value, inf.y, analyze::PowerLawOptions{0.0, s.power_law_max_excess, 4});
    if (pl.found) {
      report["beta"] = pl.beta;
      report["beta_err"] = pl.beta_err;
      report["beta_r2"] = pl.r2;
      report["beta_points"] = pl.points;
      report["beta_amplitude"] = pl.amplitude;
    } else {
      report["beta"] = nullptr;
      report["beta_r2"] = nullptr;
      report["beta_message"] = pl.message;
    }
    plot_args.insert(plot_args.end(), {"--qi", fmt::format("{:.17g}", inf.x), "--cni", fmt::format("{:.17g}", inf.y),
                                       "--slope", fmt::format("{:.17g}", inf.slope)});
  } else {
    report["inflection"] = nullptr;
    report["inflection_message"] = inf.message;
    report["beta"] = nullptr;
    report["beta_r2"] = nullptr;
  }
  const double particles = static_cast<double>(p.structural + p.voids);
  report["structural"] = p.structural;
  report["voids"] = p.voids;
  report["n"] = n;
  report["phi_s"] = p.phi_s;
  report["box_edge_m"] = vem.box_edge();
  report["parameters"] = params_json(p);
  report["cycles"] = vem.cycle();
  report["rows"] = vem.curve().size();
  report["q_end"] = vem.curve().empty() ? 0.0 : vem.curve().back().q;
  report["steps"] = vem.total_steps();
  report["limited_relaxations"] = vem.limited_relaxations();
  report["stop_reason"] = generate::vem_stop_name(vem.stop_reason());
  const double m_s =
      p.structural_material.density * 4.0 / 3.0 * 3.14159265358979323846 * p.radius * p.radius * p.radius;
  report["mass_scaling"] = {
      {"void_mass_scaling", p.void_mass_scaling},
      {"void_mass_floor_kg", vem.void_mass_floor()},
      {"structural_mass_kg", m_s},
      {"unscaled_above_q",
       p.void_mass_scaling > 0.0
           ? std::cbrt(vem.void_mass_floor() /
                       (p.void_material.density * 4.0 / 3.0 * 3.14159265358979323846 * p.radius * p.radius * p.radius))
           : 0.0},
      {"note",
       "void mass = max(true mass, c m_S k_V/k_S); the voids have their true mass for q above unscaled_above_q"}};
  report["seconds"] = vem.seconds();
  report["particle_steps_per_second"] =
      vem.seconds() > 0.0 ? particles * static_cast<double>(vem.total_steps()) / vem.seconds() : 0.0;
  report["seconds_per_cycle"] = vem.cycle() > 0 ? vem.seconds() / static_cast<double>(vem.cycle()) : 0.0;
  report["threads"] = vem.engine().threads();
  io::write_report(dir / "report.json", report);
  io::PlotOptions po;
  po.enabled = s.plots;
  const bool plotted = io::make_plot("cn_curve", plot_args, dir / "cn_curve.png", po);
  if (!quiet) {
    fmt::print("VEM: {} cycles, q_end = {:.4f} ({}), {} steps in {:.1f} s ({:.3g} particle-steps/s)\n", vem.cycle(),
               report["q_end"].get<double>(), generate::vem_stop_name(vem.stop_reason()), vem.total_steps(),
               vem.seconds(), report["particle_steps_per_second"].get<double>());
    if (inf.found)
      fmt::print(
          "inflection: q_i = {:.4f} +- {:.4f}, CN_i = {:.3f}, slope = {:.2f}, Phi_T,i = {:.4f}; "
          "q_i n^1/3 = {:.3f}, slope n^1/3 = {:.2f}\n",
          inf.x, std::hypot(inf.x_err, inf.x_window), inf.y, inf.slope, report["inflection"]["phi_total"].get<double>(),
          inf.x * n13, inf.slope * n13);
    else
      fmt::print("inflection: not found ({})\n", inf.message);
    fmt::print("packing: {}\nCN(q) curve: {}{}\nreport: {}\n", (dir / "packing.xyz").string(),
               (dir / "cn_curve.csv").string(), plotted ? ", " + (dir / "cn_curve.png").string() : std::string(),
               (dir / "report.json").string());
  }
  return report;
}

}  // namespace

void add_generate_vem(CLI::App& generate) {
  struct Options {
    std::string config, out, resume;
    generate::VemParams params;
    RunSettings settings;
    std::unique_ptr<OptionFlags> method, run;
    bool no_plots = false;
    bool quiet = false;
    bool check = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = generate.add_subcommand(
      "vem", "Void expansion method: porous packings by growing void particles; CN(q) curve and its inflection point");
  cmd->add_option("--config", opt->config, "TOML file with any parameter (docs/vem.md); flags override it");
  opt->method = std::make_unique<OptionFlags>(cmd, io::vem_options(opt->params), false);
  opt->run = std::make_unique<OptionFlags>(cmd, run_settings_options(opt->settings), false);
  cmd->add_option("--out", opt->out, "Output folder");
  cmd->add_option("--resume", opt->resume, "Continue the run whose checkpoint is in this folder");
  cmd->add_flag("--no-plots", opt->no_plots, "Do not make PNG plots");
  cmd->add_flag("--check", opt->check, "Validate the parameters, print the set-up and exit without running");
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->callback([opt, cmd] {
    const auto given = [&](const char* name) { return cmd->count(name) > 0; };
    std::unique_ptr<generate::Vem> vem;
    RunSettings& settings = opt->settings;
    std::filesystem::path dir;
    if (!opt->resume.empty()) {
      // The method's parameters are the saved ones; only the threads and the run's own
      // settings may change.
      std::string refused = given("--config") ? "--config" : opt->method->first_given({"threads", "adapt_threads"});
      if (!refused.empty())
        fail_input(
            fmt::format("{} cannot be combined with --resume: the run continues with its saved parameters", refused));
      if (given("--out") && std::filesystem::path(opt->out) != std::filesystem::path(opt->resume))
        fail_input("--out: a resumed run writes into its own folder (--resume DIR); drop --out");
      dir = opt->resume;
      std::ifstream in(dir / "checkpoint.bin", std::ios::binary);
      if (!in) fail_input(fmt::format("--resume = {}: no checkpoint.bin in this folder", opt->resume));
      opt->method->apply();
      vem = generate::Vem::resume(
          in, given("--threads") ? opt->params.threads : 0,
          given("--adapt-threads") ? std::optional<bool>(opt->params.adapt_threads) : std::nullopt);
      std::uint64_t magic = 0;
      std::uint8_t plots = 1;
      binary::read(in, magic, "command settings");
      if (magic != settings_magic) fail_input("checkpoint is damaged: command settings");
      binary::read(in, settings.snapshot_every, "snapshot_every");
      binary::read(in, settings.checkpoint_seconds, "checkpoint_seconds");
      binary::read(in, settings.window_widths, "window_widths");
      binary::read(in, settings.power_law_max_excess, "power_law_max_excess");
      binary::read(in, plots, "plots");
      settings.plots = plots != 0;
      opt->run->apply();
      if (opt->no_plots) settings.plots = false;
      opt->run->schema().validate();
    } else {
      if (opt->out.empty()) fail_input("--out: required (the output folder), or --resume DIR");
      dir = opt->out;
      // default < config file < flag
      if (!opt->config.empty()) vem_schema(opt->params, settings).read_file(opt->config);
      opt->method->apply();
      opt->run->apply();
      if (opt->no_plots) settings.plots = false;
      const generate::VemParams& params = opt->params;
      params.validate();
      opt->method->schema().validate();
      opt->run->schema().validate();
      if (opt->check) {
        const double l = generate::vem_box_edge(params.structural, params.radius, params.phi_s);
        fmt::print(
            "generate vem: N_S = {}, N_V = {} (n = {:g}), Phi_S = {:g}, r_S = {:g} m, box edge {:.6g} m "
            "({:.3f} r_S), q from {:g} in steps of {:g} to at most {:g}; parameters valid\n",
            params.structural, params.voids, params.number_ratio(), params.phi_s, params.radius, l, l / params.radius,
            params.void_radius_ratio, params.void_radius_ratio, params.max_q);
        return;
      }
      io::ensure_directory(dir);
      vem = std::make_unique<generate::Vem>(params);
    }
    const auto& p = vem->params();
    if (settings.snapshot_every > 0) io::ensure_directory(dir / "snapshots");
    Progress progress("vem", static_cast<long>(std::ceil(p.max_q / p.void_radius_ratio)), !opt->quiet);
    const double energy_scale =
        static_cast<double>(p.structural) * p.structural_material.normal_stiffness * p.radius * p.radius;
    generate::Vem* v = vem.get();
    vem->on_row = [&, v](const generate::VemRow& row) {
      progress.update(row.cycle, fmt::format("q {:.3f} CN {:.3f} E/(N k r^2) {:.2e}", row.q, row.cn,
                                             row.strain_energy / energy_scale));
      if (settings.snapshot_every > 0 && row.cycle % settings.snapshot_every == 0) {
        io::WriteOptions w;
        w.comment = fmt::format("packlab generate vem snapshot cycle={} q={:.17g} cn={:.6g}", row.cycle, row.q, row.cn);
        io::write_packing(v->structural_packing(), dir / "snapshots" / fmt::format("cycle_{:05d}.xyz", row.cycle), w);
      }
    };
    // Run in pieces of about 2e6 particle-steps; checkpoint between pieces (a consistent state).
    const long chunk = std::max(100L, 2000000L / std::max(1L, p.structural + p.voids));
    auto last_checkpoint = std::chrono::steady_clock::now();
    while (!vem->run(chunk)) {
      const auto now = std::chrono::steady_clock::now();
      if (std::chrono::duration<double>(now - last_checkpoint).count() >= settings.checkpoint_seconds) {
        write_checkpoint(dir, *vem, settings);
        last_checkpoint = now;
      }
    }
    progress.finish();
    write_checkpoint(dir, *vem, settings);
    finish(dir, *vem, settings, opt->quiet);
  });
}

}  // namespace packlab::cli
