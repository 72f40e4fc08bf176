// Pieces shared by `generate ls`, `generate scrm`, `shake` and `analyze rdf`: the RDF tables,
// plots and report section (analyze_rdf.cpp) and the LS run options (generate_ls.cpp).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include <CLI/CLI.hpp>
#include <memory>
#include <optional>
#include <string>

#include "packlab/analyze/rdf.hpp"
#include "packlab/core/packing.hpp"
#include "packlab/generate/ls.hpp"
#include "packlab/cli/checkpoint.hpp"
#include "packlab/cli/options.hpp"
#include "packlab/io/config.hpp"
#include "packlab/io/options.hpp"

namespace packlab::cli {

// Per class volume fraction (largest radius first, as Rdf's classes) of a packing.
std::vector<double> class_volume_fractions(const Packing& packing, const std::vector<double>& class_radius);

// DIR/rdf.csv (r, R, K, g, I and the well-stirred and Willis curves), DIR/rdf_partial.csv
// (when `partial` and there are several classes), DIR/windows.csv, PNG plots of each unless
// plots are off; returns the report section (contact values with their Percus-Yevick values,
// first peaks, window statistics).
nlohmann::json write_rdf_outputs(const analyze::Rdf& rdf, const std::vector<double>& class_volume_fraction,
                                 const std::filesystem::path& dir, bool partial, bool plots);

// The command's side of `generate ls` and `generate scrm` (the method's options are
// io::ls_options / io::scrm_options): output folder, config file, the RDF of the result and,
// for a resumable command, the checkpoints (cli/checkpoint.hpp).
struct LsRunOptions {
  std::string out;
  analyze::RdfParams rdf;
  bool no_plots = false, quiet = false;
  std::unique_ptr<OptionFlags> flags;
  std::string resume;               // --resume DIR
  double checkpoint_seconds = 120;  // output.checkpoint_seconds
  std::optional<SavedRun> resumed;  // the saved run when resuming
};
// The option set of the command: `method`, the RDF of the result and, when `resumable`,
// output.checkpoint_seconds.
io::ConfigSchema ls_run_schema(const io::ConfigSchema& method, LsRunOptions& run, bool resumable);
// --config, the flags of ls_run_schema(), --out, --no-plots, --quiet and, when `resumable`,
// --resume DIR.
void add_ls_run_options(CLI::App& cmd, LsRunOptions& run, const io::ConfigSchema& method, bool resumable = false);
// Defaults, then the config file, then the flags; or, with --resume DIR, the saved settings.
void resolve_ls_run_options(LsRunOptions& run);
// The report's parameters of an LS start (with the normalized number fractions and the counts).
nlohmann::json ls_parameters(const io::LsOptions& o);

// The RDF of the result as the command's own settings: rdf.dr (--rdf-dr), rdf.r_max (--rdf-r-max).
io::ConfigSchema rdf_output_options(const std::string& command, analyze::RdfParams& rdf);

// Writes DIR/packing.xyz and DIR/packing.vtu (with a provenance comment).
void write_packing_outputs(const Packing& packing, const std::filesystem::path& dir, const std::string& comment);

// The RDF of one packing (dr, rmax in units of the largest radius), written with write_rdf_outputs.
nlohmann::json rdf_of(const Packing& packing, const std::filesystem::path& dir, double dr, double rmax, bool plots);

}  // namespace packlab::cli
