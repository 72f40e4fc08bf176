// Calibration of an inverse-opal model by uniaxial compression (bpm-inverse-opals eq. 18-20),
// the workflow behind `packlab calibrate compress` and packlab.calibrate_compress:
//  - calibrate_compression: Newton iteration with finite-difference derivatives
//    (mechanics/calibration.hpp) on the silica bond Young's modulus E_b and strength sigma_max
//    (= tau_max) until the test gives the target Young's modulus and strength. Each evaluation
//    changes those two values only; the strain rate stays the one the set-up fixed from the
//    starting values.
//  - compression_bulk_factor: one test of a pore-free sample, K_E = E_macro / E_b (eq. 20), and
//    the strength ratios.
#pragma once

#include <functional>
#include <vector>

#include "packlab/core/columns.hpp"
#include "packlab/core/packing.hpp"
#include "packlab/mechanics/calibration.hpp"
#include "packlab/mechanics/opal_materials.hpp"
#include "packlab/mechanics/uniaxial_compression.hpp"

namespace packlab::mechanics {

struct CompressionCalibrationResult {
  CalibrationResult calibration;    // parameters {E_b, sigma_max}, responses {E, strength}
  UniaxialCompressionResult final;  // the run at calibration.parameters
  bool has_final = false;
};

// Called after each simulation: its number (1-based), parameters {E_b, sigma_max} and result.
using CompressionRunCallback =
    std::function<void(int run, const std::vector<double>& parameters, const UniaxialCompressionResult& result)>;

// InputError unless both targets are > 0 Pa. `setup` is finished (UniaxialCompressionSetup::finish).
// `progress` (optional) makes the run resumable (mechanics/calibration.hpp): the dynamic
// solver's checkpoints of the running simulation go to progress->checkpoint.
CompressionCalibrationResult calibrate_compression(const Packing& model, const UniaxialCompressionSetup& setup,
                                                   double target_youngs_modulus, double target_strength,
                                                   const CalibrationOptions& options,
                                                   const CompressionRunCallback& on_run = {},
                                                   CalibrationProgress* progress = nullptr);

// Every simulation of a calibration in order: evaluation, finite_difference (flag),
// bond_youngs_modulus, bond_strength, youngs_modulus, strength.
Columns calibration_history_columns(const CalibrationResult& calibration);

struct BulkFactorResult {
  UniaxialCompressionResult run;
  double bulk_factor = 0.0;      // K_E = E_macro / E_b [-]
  double strength_ratio = 0.0;   // E_macro / strength [-]
  double strength_factor = 0.0;  // strength / sigma_max [-]
};
BulkFactorResult compression_bulk_factor(const Packing& model, const UniaxialCompressionSetup& setup);

}  // namespace packlab::mechanics
