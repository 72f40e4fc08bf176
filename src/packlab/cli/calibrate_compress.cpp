// packlab calibrate compress IN --target-youngs-modulus E --target-strength S --out DIR [compression flags]
// packlab calibrate compress IN --bulk-factor --out DIR [compression flags]
// 1. Newton iteration with finite-difference derivatives (bpm-inverse-opals eq. 18-19,
//    mechanics/calibration.hpp) on the silica bond Young's modulus E_b and strength sigma_max
//    (= tau_max) until the compression test gives the target E* and strength to --tolerance
//    (0.5 %); the paper's one-parameter-per-response scheme (--full-jacobian for all terms).
// 2. --bulk-factor: one compression test of a pore-free sample: K_E = E_macro / E_b (eq. 20)
//    and the strength ratio E_macro / strength (the paper: 3.35 and ~35).
// Writes DIR/report.json, DIR/calibration.csv and the compression outputs of the final
// parameters in DIR/final/.
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>

#include "packlab/cli/commands.hpp"
#include "packlab/cli/uniaxial_compression_output.hpp"
#include "packlab/core/error.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/report.hpp"
#include "packlab/io/table.hpp"
#include "packlab/mechanics/compression_calibration.hpp"

namespace packlab::cli {

// Defined in uniaxial_compression.cpp: the flags and config keys of a compression run.
struct CompressFlags;
std::shared_ptr<CompressFlags> add_compression_flags(CLI::App* cmd);
mechanics::UniaxialCompressionSetup resolve_compression_settings(CLI::App* cmd, const CompressFlags& f, const std::string& config,
                                                         const Packing& model);
using CompressSettings = mechanics::UniaxialCompressionSetup;

namespace {

nlohmann::json history_json(const mechanics::CalibrationResult& c) {
  nlohmann::json history = nlohmann::json::array();
  for (const auto& h : c.history)
    history.push_back({{"bond_youngs_modulus", h.parameters[0]},
                       {"bond_strength", h.parameters[1]},
                       {"youngs_modulus", h.responses[0]},
                       {"strength", h.responses[1]},
                       {"finite_difference", h.finite_difference}});
  return history;
}

}  // namespace

void add_calibrate_compress(CLI::App& calibrate) {
  struct Options {
    std::string in, out, config;
    double target_e = 0.0, target_strength = 0.0;
    bool bulk_factor = false, full_jacobian = false, quiet = false, no_plots = false;
    mechanics::CalibrationOptions calibration;
    std::shared_ptr<CompressFlags> flags;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = calibrate.add_subcommand(
      "compress", "Calibrate bond Young's modulus and strength to a target (eq. 18-19), or the bulk factor K_E (eq. 20)");
  cmd->add_option("in", opt->in, "Bonded model (.vtu)")->required();
  cmd->add_option("--out", opt->out, "Output folder")->required();
  cmd->add_option("--config", opt->config, "TOML file with any compression setting; flags override it");
  cmd->add_option("--target-youngs-modulus", opt->target_e, "Target Young's modulus E* of the sample [Pa]");
  cmd->add_option("--target-strength", opt->target_strength, "Target compressive strength of the sample [Pa]");
  cmd->add_flag("--bulk-factor", opt->bulk_factor,
                "Pore-free sample: report K_E = E_macro / E_b and E_macro / strength instead of calibrating");
  cmd->add_option("--tolerance", opt->calibration.tolerance, "Relative tolerance per response")->capture_default_str();
  cmd->add_option("--max-iterations", opt->calibration.max_iterations, "Newton iterations at most")->capture_default_str();
  cmd->add_option("--relative-step", opt->calibration.relative_step, "Finite-difference step / parameter (eq. 19)")
      ->capture_default_str();
  cmd->add_flag("--full-jacobian", opt->full_jacobian,
                "Use every finite-difference derivative (default: E from E_b and strength from sigma_max only, as the paper)");
  opt->flags = add_compression_flags(cmd);
  cmd->add_flag("--no-plots", opt->no_plots, "Do not make PNG plots");
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->callback([opt, cmd] {
    const Packing model = io::read_packing(opt->in);
    CompressSettings s = resolve_compression_settings(cmd, *opt->flags, opt->config, model);
    const std::filesystem::path dir = opt->out;
    nlohmann::json report = io::report_header("calibrate compress");
    report["input"] = opt->in;
    if (opt->bulk_factor) {
      const mechanics::BulkFactorResult b = mechanics::compression_bulk_factor(model, s);
      const mechanics::UniaxialCompressionResult& r = b.run;
      write_uniaxial_compression_outputs(r, s.options, dir / "final", !opt->no_plots, false);
      report["mode"] = "bulk_factor";
      report["bond_youngs_modulus"] = s.materials.silica_youngs_modulus;
      report["bond_strength"] = s.materials.silica_strength;
      report["bulk_factor"] = b.bulk_factor;
      report["strength_ratio"] = b.strength_ratio;
      report["strength_factor"] = b.strength_factor;
      report["compression"] = uniaxial_compression_report(r, s.options);
      report["youngs_modulus"] = r.youngs_modulus;
      report["strength"] = r.strength;
      io::write_report(dir / "report.json", report);
      if (!opt->quiet)
        fmt::print("E_macro = {:.5g} GPa, K_E = E_macro / E_b = {:.4f}, strength {:.5g} MPa = E_macro / {:.2f} "
                   "({:.3f} x sigma_max)\n",
                   r.youngs_modulus * 1e-9, b.bulk_factor, r.strength * 1e-6, b.strength_ratio, b.strength_factor);
      return;
    }
    require(opt->target_e > 0.0, "--target-youngs-modulus", opt->target_e, "> 0 Pa (or use --bulk-factor)");
    require(opt->target_strength > 0.0, "--target-strength", opt->target_strength, "> 0 Pa");
    opt->calibration.diagonal = !opt->full_jacobian;
    auto on_run = [&](int run, const std::vector<double>& p, const mechanics::UniaxialCompressionResult& r) {
      if (!opt->quiet)
        fmt::print("run {}: E_b = {:.6g} GPa, sigma_max = {:.6g} MPa -> E = {:.6g} GPa, strength = {:.6g} MPa ({:.1f} s)\n",
                   run, p[0] * 1e-9, p[1] * 1e-6, r.youngs_modulus * 1e-9, r.strength * 1e-6, r.seconds);
      std::fflush(stdout);
    };
    const mechanics::CompressionCalibrationResult result =
        mechanics::calibrate_compression(model, s, opt->target_e, opt->target_strength, opt->calibration, on_run);
    const mechanics::CalibrationResult& c = result.calibration;
    const Columns history = mechanics::calibration_history_columns(c);
    std::filesystem::create_directories(dir);
    io::write_text_atomically(dir / "calibration.csv", io::to_csv(history));
    if (result.has_final)
      write_uniaxial_compression_outputs(result.final, s.options, dir / "final", !opt->no_plots, false);
    report["mode"] = "calibrate";
    report["targets"] = {{"youngs_modulus", opt->target_e}, {"strength", opt->target_strength}};
    report["tolerance"] = opt->calibration.tolerance;
    report["scheme"] = opt->full_jacobian ? "full finite-difference Jacobian" : "diagonal (paper: dE/dsigma = dS/dE_b = 0)";
    report["converged"] = c.converged;
    report["iterations"] = c.iterations;
    report["simulations"] = c.evaluations;
    report["bond_youngs_modulus"] = c.parameters[0];
    report["bond_strength"] = c.parameters[1];
    report["youngs_modulus"] = c.responses[0];
    report["strength"] = c.responses[1];
    report["history"] = history_json(c);
    io::write_report(dir / "report.json", report);
    if (!opt->quiet)
      fmt::print("{}: E_b = {:.6g} GPa, sigma_max = {:.6g} MPa give E = {:.6g} GPa, strength = {:.6g} MPa\n", c.reason(),
                 c.parameters[0] * 1e-9, c.parameters[1] * 1e-6, c.responses[0] * 1e-9, c.responses[1] * 1e-6);
    if (!c.converged) fail_input("calibration did not converge: " + c.reason());
  });
}

}  // namespace packlab::cli
