// The outputs of a uniaxial compression run, shared by `packlab test compress` and
// `packlab calibrate compress`: the report's results block and the CSV, VTU and PNG files.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "packlab/mechanics/uniaxial_compression.hpp"

namespace packlab::cli {

// The results as JSON (SI units; keys youngs_modulus, strength, broken_bonds, ...).
nlohmann::json uniaxial_compression_report(const mechanics::UniaxialCompressionResult& result,
                                           const mechanics::UniaxialCompressionOptions& options);

// Writes into `dir`: curve.csv (+ stress_strain.png, force_displacement.png, broken_bonds.png),
// bond_strain.csv (+ bond_strain.png, Fig. 7) and particle_stress.csv when snapshots were taken,
// broken_bonds.csv and broken_bonds.vtu (failure positions with time and strain), model.vtu
// (final state, bond states) when `write_model`. Plots only when `plots`.
void write_uniaxial_compression_outputs(const mechanics::UniaxialCompressionResult& result,
                                        const mechanics::UniaxialCompressionOptions& options,
                                        const std::filesystem::path& dir, bool plots, bool write_model);

}  // namespace packlab::cli
