// Pieces shared by `generate ls`, `generate scrm`, `shake` and `analyze rdf`: the RDF tables,
// plots and report section (analyze_rdf.cpp) and the LS options (generate_ls.cpp).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "packlab/analyze/rdf.hpp"
#include "packlab/core/packing.hpp"
#include "packlab/generate/ls.hpp"

namespace packlab::cli {

// Per class volume fraction (largest radius first, as Rdf's classes) of a packing.
std::vector<double> class_volume_fractions(const Packing& packing, const std::vector<double>& class_radius);

// DIR/rdf.csv (r, R, K, g, I and the well-stirred and Willis curves), DIR/rdf_partial.csv
// (when `partial` and there are several classes), DIR/windows.csv, PNG plots of each unless
// plots are off; returns the report section (contact values with their Percus-Yevick values,
// first peaks, window statistics).
nlohmann::json write_rdf_outputs(const analyze::Rdf& rdf, const std::vector<double>& class_volume_fraction,
                                 const std::filesystem::path& dir, bool partial, bool plots);

// Options of an LS run from random points (generate ls and generate scrm).
struct LsRunOptions {
  double phi = 0.0;  // 0 = to jamming
  long particles = 2000;
  std::vector<double> sizes{1.0};
  std::vector<double> number_fractions, volume_fractions;
  double radius = 0.5;
  generate::LsParams ls;
  std::uint64_t seed = 1;
  std::string out;
  double rdf_dr = 0.01, rdf_rmax = 8.0;
  bool no_plots = false, quiet = false;
  generate::SizeClasses classes() const;
  nlohmann::json parameters() const;
};
void add_ls_options(CLI::App& cmd, LsRunOptions& opt);

// Writes DIR/packing.xyz and DIR/packing.vtu (with a provenance comment).
void write_packing_outputs(const Packing& packing, const std::filesystem::path& dir, const std::string& comment);

// The RDF of one packing (dr, rmax in units of the largest radius), written with write_rdf_outputs.
nlohmann::json rdf_of(const Packing& packing, const std::filesystem::path& dir, double dr, double rmax, bool plots);

}  // namespace packlab::cli
