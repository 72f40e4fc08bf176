// packlab calibrate shear IN --target-storage-modulus PA [--config FILE] [test shear flags] --out DIR
// Finds the particle normal stiffness k_n (k_s following at the ratio of the options) for which
// the mean storage modulus G' of the structure matches the target (doh-elastic-properties §3.1:
// k_n was calibrated in 50-150 N/m); Newton with a finite-difference derivative
// (mechanics::calibrate). Writes DIR/calibration.csv (every evaluation) and DIR/report.json.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <sstream>

#include "packlab/cli/commands.hpp"
#include "packlab/core/error.hpp"
#include "packlab/io/atomic_file.hpp"
#include "packlab/io/config.hpp"
#include "packlab/io/packing_io.hpp"
#include "packlab/io/report.hpp"
#include "packlab/mechanics/shear_calibration.hpp"

namespace packlab::cli {

// Defined in oscillatory_shear.cpp (the flags and config keys both shear commands share).
std::function<void(mechanics::OscillatoryShearOptions&, std::string&, bool&)> add_shear_flags(CLI::App* cmd,
                                                                                       const std::string& command);
nlohmann::json shear_parameters_json(const mechanics::OscillatoryShearOptions& t, const std::string& orientations);

void add_calibrate_shear(CLI::App& calibrate) {
  struct Options {
    std::string in, out;
    double target = 0.0;
    double tolerance = 0.005;
    int max_iterations = 10;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = calibrate.add_subcommand(
      "shear", "Calibrate the particle normal stiffness k_n so that the storage modulus G' matches a target");
  cmd->add_option("in", opt->in, "Bonded model (a file with bonds)")->required();
  cmd->add_option("--target-storage-modulus", opt->target, "Target G' [Pa]")->required();
  cmd->add_option("--tolerance", opt->tolerance, "Relative tolerance on G'")->capture_default_str();
  cmd->add_option("--max-iterations", opt->max_iterations, "Newton iterations at most")->capture_default_str();
  cmd->add_option("--out", opt->out, "Output folder")->required();
  auto apply = add_shear_flags(cmd, "calibrate shear");
  cmd->add_flag("--quiet", opt->quiet, "No progress output");
  cmd->callback([opt, apply] {
    mechanics::OscillatoryShearOptions options;
    std::string orientations;
    bool plots = true;
    apply(options, orientations, plots);
    require(opt->target > 0.0 && std::isfinite(opt->target), "--target-storage-modulus", opt->target, "> 0 Pa");
    const Packing packing = io::read_packing(opt->in);
    const std::filesystem::path dir = opt->out;
    io::ensure_directory(dir);
    const auto result =
        mechanics::calibrate_normal_stiffness(packing, opt->target, options, opt->tolerance, opt->max_iterations);
    std::ostringstream csv;
    csv << "evaluation,normal_stiffness,shear_stiffness,storage_modulus\n";
    const double ratio = options.shear_stiffness / options.normal_stiffness;
    for (std::size_t k = 0; k < result.tried_normal_stiffness.size(); ++k)
      csv << fmt::format("{},{:.10g},{:.10g},{:.10g}\n", k + 1, result.tried_normal_stiffness[k],
                         ratio * result.tried_normal_stiffness[k], result.tried_storage_modulus[k]);
    io::write_text_atomically(dir / "calibration.csv", csv.str());
    nlohmann::json report = io::report_header("calibrate shear");
    report["input"] = opt->in;
    report["parameters"] = shear_parameters_json(options, orientations);
    report["target_storage_modulus"] = opt->target;
    report["tolerance"] = opt->tolerance;
    report["normal_stiffness"] = result.normal_stiffness;
    report["shear_stiffness"] = result.shear_stiffness;
    report["storage_modulus"] = result.storage_modulus;
    report["converged"] = result.converged;
    report["iterations"] = result.iterations;
    report["evaluations"] = result.evaluations;
    report["reason"] = result.reason;
    report["units"] = {{"normal_stiffness", "N/m"}, {"storage_modulus", "Pa"}};
    io::write_report(dir / "report.json", report);
    if (!opt->quiet)
      fmt::print("k_n = {:.6g} N/m (k_s = {:.6g} N/m): G' = {:.6g} Pa for the target {:.6g} Pa; {}\n",
                 result.normal_stiffness, result.shear_stiffness, result.storage_modulus, opt->target, result.reason);
    if (!result.converged) fail_input("calibrate shear: " + result.reason);
  });
}

}  // namespace packlab::cli
