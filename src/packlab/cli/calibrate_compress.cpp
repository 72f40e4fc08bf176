// packlab calibrate compress IN --target-youngs-modulus E --target-strength S --out DIR [options of test compress]
// packlab calibrate compress IN --bulk-factor --out DIR [options of test compress]
// 1. Newton iteration with finite-difference derivatives (bpm-inverse-opals eq. 18-19,
//    mechanics/calibration.hpp) on the silica bond Young's modulus E_b and strength sigma_max
//    (= tau_max) until the compression test gives the target E* and strength to --tolerance
//    (0.5 %); the paper's one-parameter-per-response scheme (--full-jacobian for all terms).
// 2. --bulk-factor: one compression test of a pore-free sample: K_E = E_macro / E_b (eq. 20)
//    and the strength ratio E_macro / strength (the paper: 3.35 and ~35).
// Writes DIR/report.json, DIR/calibration.csv and the compression outputs of the final
// parameters in DIR/final/.
// packlab calibrate compress --resume DIR [--threads T] [--adapt-threads=false]
// DIR/checkpoint.bin is written after every simulation and every --checkpoint-seconds within
// one (dynamic solver); --resume DIR replays the finished simulations, goes on with the one
// that was running and ends with the same files as an uninterrupted run.
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>

#include "packlab/cli/checkpoint.hpp"
#include "packlab/cli/commands.hpp"
#include "packlab/cli/options.hpp"
#include "packlab/cli/uniaxial_compression_output.hpp"
#include "packlab/core/error.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/mechanics_report.hpp"
#include "packlab/io/options.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/report.hpp"
#include "packlab/io/table.hpp"
#include "packlab/mechanics/compression_calibration.hpp"

namespace packlab::cli {

void add_calibrate_compress(CLI::App& calibrate) {
  add_option_command(
      calibrate, "compress",
      "Calibrate bond Young's modulus and strength to a target (eq. 18-19), or the bulk factor K_E (eq. 20)",
      io::compression_calibration_options,
      {.input = "Bonded model (.vtu)", .output = "Output folder", .plots = true, .resumable = true},
      [](OptionCommand<io::CompressionCalibrationRun>& command) {
        io::CompressionCalibrationRun run = command.settings;
        const Packing model = io::read_packing(command.in);
        mechanics::UniaxialCompressionSetup& s = run.setup;
        s.finish(model);
        s.options.validate();
        if (!run.bulk_factor) {
          require(run.target_youngs_modulus > 0.0, "--target-youngs-modulus", run.target_youngs_modulus,
                  "> 0 Pa (or use --bulk-factor)");
          require(run.target_strength > 0.0, "--target-strength", run.target_strength, "> 0 Pa");
        }
        const std::filesystem::path dir = command.out;
        const io::OutputFolder folder(dir);  // removed again when the model is refused
        nlohmann::json report = io::report_header("calibrate compress");
        report["input"] = command.in;
        CheckpointWriter checkpoint(dir, command.flags->schema(), command.in, s.checkpoint_seconds);
        mechanics::CalibrationProgress progress =
            calibration_progress(checkpoint, command.resumed ? &*command.resumed : nullptr);
        if (!command.quiet && !progress.done.empty())
          fmt::print("resumed: {} finished simulations replayed from {}\n", progress.done.size(),
                     checkpoint_path(dir).string());
        if (run.bulk_factor) {
          // One simulation: resumable within it (either solver's checkpoints).
          progress.attach({s.materials.silica_youngs_modulus, s.materials.silica_strength}, s.options.resume,
                          s.options.checkpoint);
          const mechanics::BulkFactorResult b = mechanics::compression_bulk_factor(model, s);
          const mechanics::UniaxialCompressionResult& r = b.run;
          write_uniaxial_compression_outputs(r, s.options, dir / "final", !command.no_plots, false);
          report.update(io::bulk_factor_summary(b, s));
          io::write_report(dir / "report.json", report);
          if (!command.quiet)
            fmt::print(
                "E_macro = {:.5g} GPa, K_E = E_macro / E_b = {:.4f}, strength {:.5g} MPa = E_macro / {:.2f} "
                "({:.3f} x sigma_max)\n",
                r.youngs_modulus * 1e-9, b.bulk_factor, r.strength * 1e-6, b.strength_ratio, b.strength_factor);
          return;
        }
        run.calibration.diagonal = !run.full_jacobian;
        auto on_run = [&](int simulation, const std::vector<double>& p, const mechanics::UniaxialCompressionResult& r) {
          if (!command.quiet)
            fmt::print(
                "run {}: E_b = {:.6g} GPa, sigma_max = {:.6g} MPa -> E = {:.6g} GPa, strength = {:.6g} MPa ({:.1f} "
                "s)\n",
                simulation, p[0] * 1e-9, p[1] * 1e-6, r.youngs_modulus * 1e-9, r.strength * 1e-6, r.seconds);
          std::fflush(stdout);
        };
        const mechanics::CompressionCalibrationResult result = mechanics::calibrate_compression(
            model, s, run.target_youngs_modulus, run.target_strength, run.calibration, on_run, &progress);
        const mechanics::CalibrationResult& c = result.calibration;
        const Columns history = mechanics::calibration_history_columns(c);
        io::write_text_atomically(dir / "calibration.csv", io::to_csv(history));
        if (result.has_final)
          write_uniaxial_compression_outputs(result.final, s.options, dir / "final", !command.no_plots, false);
        report.update(io::compression_calibration_summary(result, run.calibration));
        io::write_report(dir / "report.json", report);
        if (!command.quiet)
          fmt::print("{}: E_b = {:.6g} GPa, sigma_max = {:.6g} MPa give E = {:.6g} GPa, strength = {:.6g} MPa\n",
                     c.reason(), c.parameters[0] * 1e-9, c.parameters[1] * 1e-6, c.responses[0] * 1e-9,
                     c.responses[1] * 1e-6);
        if (!c.converged) fail_input("calibration did not converge: " + c.reason());
      });
}

}  // namespace packlab::cli
