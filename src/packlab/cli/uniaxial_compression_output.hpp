// The outputs of a uniaxial compression run, shared by `packlab test compress` and
// `packlab calibrate compress`: the CSV, VTU and PNG files (the report: io/mechanics_report.hpp).
#pragma once

#include <filesystem>

#include "packlab/mechanics/uniaxial_compression.hpp"

namespace packlab::cli {

// Writes into `dir`: curve.csv (+ stress_strain.png, force_displacement.png, broken_bonds.png),
// bond_strain.csv (+ bond_strain.png, Fig. 7) and particle_stress.csv when snapshots were taken,
// broken_bonds.csv and broken_bonds.vtu (failure positions with time and strain), model.vtu
// (final state, bond states) when `write_model`. Plots only when `plots`.
void write_uniaxial_compression_outputs(const mechanics::UniaxialCompressionResult& result,
                                        const mechanics::UniaxialCompressionOptions& options,
                                        const std::filesystem::path& dir, bool plots, bool write_model);

}  // namespace packlab::cli
