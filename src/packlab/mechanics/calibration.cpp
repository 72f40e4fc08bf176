#include "packlab/mechanics/calibration.hpp"

// GCC 12 reports a false -Wmaybe-uninitialized inside Eigen's AVX-512 kernels (see analyze/fits.cpp).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "packlab/core/error.hpp"

namespace packlab::mechanics {

std::string CalibrationResult::reason() const {
  return converged ? fmt::format("converged in {} iterations ({} simulations)", iterations, evaluations)
                   : fmt::format("not converged after {} iterations ({} simulations)", iterations, evaluations);
}

std::istream* CalibrationProgress::take_resume(const std::vector<double>& parameters) {
  if (running_state == nullptr || running != parameters) return nullptr;
  std::istream* state = running_state;
  running_state = nullptr;
  running.clear();
  return state;
}

void CalibrationProgress::attach(const std::vector<double>& parameters, std::istream*& resume,
                                 TestCheckpoint& test_checkpoint) {
  resume = take_resume(parameters);
  if (checkpoint)
    test_checkpoint = [this, parameters](const std::function<void(std::ostream&)>& state, bool end) {
      if (!end) checkpoint(parameters, state);
    };
}

CalibrationResult calibrate(const ResponseFunction& response, const std::vector<double>& start,
                            const std::vector<double>& targets, const CalibrationOptions& options,
                            CalibrationProgress* progress) {
  const std::size_t n = start.size();
  require(n >= 1 && n == targets.size(), "parameters", static_cast<double>(n),
          fmt::format("as many as the targets ({}), at least one", targets.size()));
  for (std::size_t a = 0; a < n; ++a) {
    require(std::isfinite(start[a]) && start[a] > 0.0, fmt::format("start[{}]", a), start[a], "positive");
    require(std::isfinite(targets[a]) && targets[a] > 0.0, fmt::format("target[{}]", a), targets[a], "positive");
  }
  require(options.tolerance > 0.0 && options.tolerance < 1.0, "tolerance", options.tolerance, "in (0, 1)");
  require(options.max_iterations >= 1 && options.max_iterations <= 1000, "max_iterations", options.max_iterations,
          "in [1, 1000]");
  require(options.relative_step > 0.0 && options.relative_step < 1.0, "relative_step", options.relative_step,
          "in (0, 1)");
  require(options.lower.empty() || options.lower.size() == n, "lower bounds", static_cast<double>(options.lower.size()),
          "empty or one per parameter");
  require(options.upper.empty() || options.upper.size() == n, "upper bounds", static_cast<double>(options.upper.size()),
          "empty or one per parameter");

  CalibrationResult result;
  auto evaluate = [&](const std::vector<double>& p, bool finite_difference) {
    const std::size_t k = result.history.size();
    std::vector<double> r;
    if (progress != nullptr && k < progress->done.size()) {
      // Replay: the same parameters, bit for bit, or the checkpoint is not of this run.
      const CalibrationStep& saved = progress->done[k];
      if (saved.parameters != p || saved.finite_difference != finite_difference || saved.responses.size() != n)
        fail_input(fmt::format(
            "calibration checkpoint: evaluation {} was at other parameters than the resumed run asks for (a "
            "checkpoint of another run or model)",
            k + 1));
      r = saved.responses;
    } else {
      r = response(p);
    }
    require(r.size() == n, "responses", static_cast<double>(r.size()), fmt::format("{} values", n));
    ++result.evaluations;
    result.history.push_back({p, r, finite_difference});
    if (progress != nullptr && k >= progress->done.size() && progress->on_evaluation)
      progress->on_evaluation(result.history);
    return r;
  };
  auto converged = [&](const std::vector<double>& r) {
    for (std::size_t a = 0; a < n; ++a)
      if (!(std::abs(r[a] - targets[a]) <= options.tolerance * targets[a])) return false;
    return true;
  };

  std::vector<double> p = start;
  std::vector<double> r = evaluate(p, false);
  while (!converged(r) && result.iterations < options.max_iterations) {
    // eq. 19: forward differences, one simulation per parameter.
    Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
    for (std::size_t b = 0; b < n; ++b) {
      std::vector<double> q = p;
      const double step = options.relative_step * p[b];
      q[b] += step;
      const std::vector<double> rq = evaluate(q, true);
      for (std::size_t a = 0; a < n; ++a)
        if (!options.diagonal || a == b)
          jacobian(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) = (rq[a] - r[a]) / step;
    }
    Eigen::VectorXd residual(static_cast<Eigen::Index>(n));
    for (std::size_t a = 0; a < n; ++a) residual(static_cast<Eigen::Index>(a)) = targets[a] - r[a];
    // eq. 18: the Newton step. A response that does not move with its parameter cannot be
    // calibrated: say so instead of dividing by zero.
    Eigen::FullPivLU<Eigen::MatrixXd> lu(jacobian);
    if (!lu.isInvertible())
      fail_input(
          "calibration: the responses do not change with the parameters (singular finite-difference "
          "Jacobian); check the parameter ranges");
    const Eigen::VectorXd delta = lu.solve(residual);
    for (std::size_t a = 0; a < n; ++a) {
      double next = p[a] + delta(static_cast<Eigen::Index>(a));
      // Keep parameters physical: never below a tenth of the current value (a secant through
      // noise must not send a stiffness negative), within the bounds when given.
      next = std::max(next, 0.1 * p[a]);
      if (!options.lower.empty()) next = std::max(next, options.lower[a]);
      if (!options.upper.empty()) next = std::min(next, options.upper[a]);
      p[a] = next;
    }
    ++result.iterations;
    r = evaluate(p, false);
  }
  result.parameters = p;
  result.responses = r;
  result.converged = converged(r);
  return result;
}

}  // namespace packlab::mechanics
