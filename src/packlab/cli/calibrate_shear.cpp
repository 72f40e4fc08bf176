// packlab calibrate shear IN --target-storage-modulus PA [--config FILE] [the options of test shear] --out DIR
// Finds the particle normal stiffness k_n (k_s following at the ratio of the options) for which
// the mean storage modulus G' of the structure matches the target (doh-elastic-properties §3.1:
// k_n was calibrated in 50-150 N/m); Newton with a finite-difference derivative
// (mechanics::calibrate). Writes DIR/calibration.csv (every evaluation) and DIR/report.json.
// packlab calibrate shear --resume DIR [--threads T] [--adapt-threads=false]: DIR/checkpoint.bin
// is written after every simulation and every --checkpoint-seconds within one (dynamic solver);
// the resumed run relaxes the structure again (deterministic), replays the finished simulations
// and goes on with the one that was running, ending with the same files as an uninterrupted run.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <sstream>

#include "packlab/cli/checkpoint.hpp"
#include "packlab/cli/commands.hpp"
#include "packlab/cli/options.hpp"
#include "packlab/core/error.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/options.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/report.hpp"
#include "packlab/mechanics/shear_calibration.hpp"

namespace packlab::cli {

void add_calibrate_shear(CLI::App& calibrate) {
  add_option_command(
      calibrate, "shear", "Calibrate the particle normal stiffness k_n so that the storage modulus G' matches a target",
      io::shear_calibration_options,
      {.input = "Bonded model (a file with bonds)", .output = "Output folder", .resumable = true},
      [](OptionCommand<io::ShearCalibrationRun>& c) {
        // The target is required: its default 0 is outside its range, so the range check stopped it.
        const io::ShearCalibrationRun& run = c.settings;
        const mechanics::OscillatoryShearOptions& options = run.test;
        mechanics::validate(options);
        const Packing packing = io::read_packing(c.in);
        const std::filesystem::path dir = c.out;
        const io::OutputFolder folder(dir);  // removed again when the model is refused
        CheckpointWriter checkpoint(dir, c.flags->schema(), c.in, run.checkpoint_seconds);
        mechanics::CalibrationProgress progress = calibration_progress(checkpoint, c.resumed ? &*c.resumed : nullptr);
        if (!c.quiet && !progress.done.empty())
          fmt::print("resumed: {} finished simulations replayed from {}\n", progress.done.size(),
                     checkpoint_path(dir).string());
        const auto result =
            mechanics::calibrate_normal_stiffness(packing, run.target_storage_modulus, options, run.tolerance,
                                                  static_cast<int>(run.max_iterations), &progress);
        std::ostringstream csv;
        csv << "evaluation,normal_stiffness,shear_stiffness,storage_modulus\n";
        const double ratio = options.shear_stiffness / options.normal_stiffness;
        for (std::size_t k = 0; k < result.tried_normal_stiffness.size(); ++k)
          csv << fmt::format("{},{:.10g},{:.10g},{:.10g}\n", k + 1, result.tried_normal_stiffness[k],
                             ratio * result.tried_normal_stiffness[k], result.tried_storage_modulus[k]);
        io::write_text_atomically(dir / "calibration.csv", csv.str());
        nlohmann::json report = io::report_header("calibrate shear");
        report["input"] = c.in;
        report["parameters"] = c.flags->schema().json();
        report["normal_stiffness"] = result.normal_stiffness;
        report["shear_stiffness"] = result.shear_stiffness;
        report["storage_modulus"] = result.storage_modulus;
        report["converged"] = result.converged;
        report["iterations"] = result.iterations;
        report["evaluations"] = result.evaluations;
        report["reason"] = result.reason;
        report["units"] = {{"normal_stiffness", "N/m"}, {"storage_modulus", "Pa"}};
        io::write_report(dir / "report.json", report);
        if (!c.quiet)
          fmt::print("k_n = {:.6g} N/m (k_s = {:.6g} N/m): G' = {:.6g} Pa for the target {:.6g} Pa; {}\n",
                     result.normal_stiffness, result.shear_stiffness, result.storage_modulus,
                     run.target_storage_modulus, result.reason);
        if (!result.converged) fail_input("calibrate shear: " + result.reason);
      });
}

}  // namespace packlab::cli
