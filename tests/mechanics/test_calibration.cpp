#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "packlab/core/error.hpp"
#include "packlab/mechanics/calibration.hpp"

using namespace packlab;
using namespace packlab::mechanics;

TEST(Calibration, LinearResponseConvergesInOneNewtonStep) {
  // G' linear in kn (doh-elastic-properties Fig. 5): one secant step is exact.
  int calls = 0;
  auto response = [&](const std::vector<double>& p) {
    ++calls;
    return std::vector<double>{0.0173 * p[0]};
  };
  const CalibrationResult result = calibrate(response, {100.0}, {1.17});
  EXPECT_TRUE(result.converged);
  EXPECT_EQ(result.iterations, 1);
  EXPECT_EQ(calls, 3);  // start, finite difference, the new iterate
  EXPECT_NEAR(result.parameters[0], 1.17 / 0.0173, 1e-9 * 1.17 / 0.0173);
}

TEST(Calibration, NonlinearTwoParametersWithCrossTermsReachTolerance) {
  // E(E_b, s) = 0.3 E_b^1.1 + 0.01 s, strength(E_b, s) = 0.4 s^0.9 + 1e-3 E_b
  auto response = [](const std::vector<double>& p) {
    return std::vector<double>{0.3 * std::pow(p[0], 1.1) + 0.01 * p[1], 0.4 * std::pow(p[1], 0.9) + 1e-3 * p[0]};
  };
  const std::vector<double> targets{2.0e3, 60.0};
  CalibrationOptions options;
  options.tolerance = 1e-3;
  const CalibrationResult result = calibrate(response, {1.0e3, 50.0}, targets, options);
  ASSERT_TRUE(result.converged) << result.reason();
  for (int a = 0; a < 2; ++a) EXPECT_LE(std::abs(result.responses[a] - targets[a]), 1e-3 * targets[a]);
  EXPECT_LE(result.iterations, 6);
  // The paper's diagonal scheme converges too when the cross terms are weak.
  options.diagonal = true;
  EXPECT_TRUE(calibrate(response, {1.0e3, 50.0}, targets, options).converged);
}

TEST(Calibration, InsensitiveResponseIsAnInputError) {
  auto response = [](const std::vector<double>&) { return std::vector<double>{1.0}; };
  EXPECT_THROW(calibrate(response, {1.0}, {2.0}), InputError);
  EXPECT_THROW(calibrate(response, {-1.0}, {2.0}), InputError);
  EXPECT_THROW(calibrate(response, {1.0, 2.0}, {2.0}), InputError);
}

TEST(Calibration, StopsAtIterationLimitAndSaysSo) {
  // A response with a plateau beyond reach: never converges, reports it.
  auto response = [](const std::vector<double>& p) { return std::vector<double>{p[0] / (1.0 + p[0])}; };
  CalibrationOptions options;
  options.max_iterations = 4;
  const CalibrationResult result = calibrate(response, {1.0}, {1.5}, options);
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.iterations, 4);
  EXPECT_NE(result.reason().find("not converged"), std::string::npos);
}

TEST(Calibration, ResumedRunReplaysTheFinishedEvaluationsAndSimulatesOnlyTheRest) {
  // A straight run records its evaluations; a second run given the first three replays them
  // (no call) and simulates the rest: the same iterates and result, bit for bit.
  auto response = [](const std::vector<double>& p) {
    return std::vector<double>{0.3 * std::pow(p[0], 1.1) + 0.01 * p[1], 0.4 * std::pow(p[1], 0.9) + 1e-3 * p[0]};
  };
  CalibrationOptions options;
  options.tolerance = 1e-4;
  std::vector<CalibrationStep> recorded;
  CalibrationProgress straight;
  straight.on_evaluation = [&](const std::vector<CalibrationStep>& so_far) { recorded = so_far; };
  const CalibrationResult a = calibrate(response, {1.0e3, 50.0}, {2.0e3, 60.0}, options, &straight);
  ASSERT_TRUE(a.converged);
  ASSERT_EQ(recorded.size(), a.history.size());
  ASSERT_GT(recorded.size(), 4u);

  int calls = 0, reported = 0;
  CalibrationProgress resumed;
  resumed.done.assign(recorded.begin(), recorded.begin() + 3);
  resumed.on_evaluation = [&](const std::vector<CalibrationStep>&) { ++reported; };
  auto counted = [&](const std::vector<double>& p) {
    ++calls;
    return response(p);
  };
  const CalibrationResult b = calibrate(counted, {1.0e3, 50.0}, {2.0e3, 60.0}, options, &resumed);
  EXPECT_EQ(calls, static_cast<int>(recorded.size()) - 3);
  EXPECT_EQ(reported, calls);  // checkpoints after new evaluations only
  EXPECT_EQ(b.parameters, a.parameters);
  EXPECT_EQ(b.responses, a.responses);
  EXPECT_EQ(b.evaluations, a.evaluations);

  // A checkpoint of another run (other start parameters) is refused, not silently mixed in.
  CalibrationProgress other;
  other.done.assign(recorded.begin(), recorded.begin() + 1);
  EXPECT_THROW(calibrate(response, {1.1e3, 50.0}, {2.0e3, 60.0}, options, &other), InputError);
}

TEST(Calibration, RunningSimulationStateIsHandedOutOnceAndOnlyForItsParameters) {
  std::istringstream state("saved");
  CalibrationProgress progress;
  progress.running = {1.0, 2.0};
  progress.running_state = &state;
  EXPECT_EQ(progress.take_resume({1.0, 2.5}), nullptr);
  EXPECT_EQ(progress.take_resume({1.0, 2.0}), &state);
  EXPECT_EQ(progress.take_resume({1.0, 2.0}), nullptr);
}
