// The results of the mechanical tests as JSON (SI units): the `results` of the commands'
// report.json and the dicts the Python functions return, from one function each.
#pragma once

#include <nlohmann/json.hpp>

#include "packlab/mechanics/compression_calibration.hpp"
#include "packlab/mechanics/oscillatory_shear.hpp"
#include "packlab/mechanics/uniaxial_compression.hpp"

namespace packlab::io {

// storage_modulus {mean, std, per_orientation [...], unit}, phase_angle, bond extremes,
// relaxation, seconds, rates.
nlohmann::json oscillatory_shear_summary(const mechanics::OscillatoryShearResult& result);

// youngs_modulus, strength, broken_bonds, modulus_fit, set-up (height, area, rates), snapshots.
nlohmann::json uniaxial_compression_summary(const mechanics::UniaxialCompressionResult& result,
                                            const mechanics::UniaxialCompressionOptions& options);

// mode "calibrate": scheme, converged, reason, iterations, simulations, the bond values found,
// the responses, history (one object per simulation).
nlohmann::json compression_calibration_summary(const mechanics::CompressionCalibrationResult& result,
                                               const mechanics::CalibrationOptions& options);

// mode "bulk_factor": K_E = E_macro / E_b, the strength ratios, the compression run.
nlohmann::json bulk_factor_summary(const mechanics::BulkFactorResult& result,
                                   const mechanics::UniaxialCompressionSetup& setup);

}  // namespace packlab::io
