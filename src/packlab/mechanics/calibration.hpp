// Model calibration by Newton iteration with finite-difference derivatives
// (bpm-inverse-opals eq. 18-19): parameters p (bond Young's modulus, bond strength, contact
// stiffness, ...) are changed until the simulated responses R(p) (Young's modulus, strength,
// storage modulus, ...) match the targets R*:
//   p_{i+1} = p_i + J^-1 (R* - R(p_i)),   J_ab = (R_a(p_i + dp_b e_b) - R_a(p_i)) / dp_b   (eq. 18, 19)
// with dp_b = relative_step * p_b. With one parameter this is eq. 18 itself; with several the
// full finite-difference Jacobian is used (the paper varies E_b and sigma_max and treats each
// response as depending on its own parameter: `diagonal = true` does exactly that and costs
// the same number of simulations but ignores cross terms).
// Stops when every |R_a - R*_a| <= tolerance |R*_a|.
#pragma once

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace packlab::mechanics {

struct CalibrationOptions {
  double tolerance = 0.005;  // relative, per response (0.5 %)
  int max_iterations = 20;
  double relative_step = 0.05;  // finite-difference step dp_b / p_b
  bool diagonal = false;        // response a depends on parameter a only (the paper's scheme)
  // Parameters stay in [lower, upper] (the Newton step is clipped; empty = positive only).
  std::vector<double> lower, upper;
};

struct CalibrationStep {
  std::vector<double> parameters;
  std::vector<double> responses;
  bool finite_difference = false;  // an evaluation for a derivative, not an iterate
};

struct CalibrationResult {
  std::vector<double> parameters;        // the last iterate
  std::vector<double> responses;         // R at the last iterate
  std::vector<CalibrationStep> history;  // every evaluation in order
  int iterations = 0;
  int evaluations = 0;
  bool converged = false;
  std::string reason() const;
};

using ResponseFunction = std::function<std::vector<double>(const std::vector<double>& parameters)>;

// Resumable calibrations (`packlab calibrate compress|shear --resume`, cli/checkpoint.hpp).
// The iteration is deterministic: a resumed run asks for the same parameters in the same order,
// so the evaluations an interrupted run finished are replayed instead of simulated, and the
// simulation it was in goes on from that simulation's own checkpoint.
struct CalibrationProgress {
  std::vector<CalibrationStep> done;  // finished evaluations of the interrupted run, in order
  // The simulation the run was in: its parameters (empty: none) and its saved state (the
  // test's checkpoint), taken by the first new evaluation at exactly these parameters.
  std::vector<double> running;
  std::istream* running_state = nullptr;
  // After every new evaluation, with all evaluations so far (to write a checkpoint).
  std::function<void(const std::vector<CalibrationStep>& evaluations)> on_evaluation;
  // Within a simulation (the test's `checkpoint` hook): the parameters being simulated and the
  // writer of the test's state. Not called at the end of a simulation (on_evaluation follows).
  std::function<void(const std::vector<double>& parameters, const std::function<void(std::ostream&)>& state)>
      checkpoint;
  // The saved state for a simulation at `parameters` (once), or null.
  std::istream* take_resume(const std::vector<double>& parameters);
  // The hooks of the test that simulates `parameters` (its options' `resume` and `checkpoint`):
  // the saved state if it is the running simulation, and its checkpoints within the simulation.
  using TestCheckpoint = std::function<void(const std::function<void(std::ostream&)>& state, bool end)>;
  void attach(const std::vector<double>& parameters, std::istream*& resume, TestCheckpoint& test_checkpoint);
};

// InputError when sizes differ, a target or start value is not positive and finite, or the
// options are out of range; with `progress`, also when a replayed evaluation's parameters are
// not those the iteration asks for (the checkpoint is of another run).
CalibrationResult calibrate(const ResponseFunction& response, const std::vector<double>& start,
                            const std::vector<double>& targets, const CalibrationOptions& options = {},
                            CalibrationProgress* progress = nullptr);

}  // namespace packlab::mechanics
