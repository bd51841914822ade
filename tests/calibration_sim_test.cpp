// The calibration in the simulator against the injected truth: a smaller `eval calibration`
// with the acceptance thresholds of the full one (per parameter median |error| <= 0.1 deg,
// 95th percentile <= 0.25 deg, every trial converged, Gauss-Newton and Ceres within 0.02 deg,
// each solve <= 0.2 s, field lines reprojected within 1 px RMS), and no offsets -> zero.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "robot/Paths.h"
#include "scenarios/Calibrate.h"

namespace nao::sim {
namespace {

constexpr double kDeg = M_PI / 180;

TEST(CalibrationSim, RandomOffsetsPlacementsAndLighting) {
  CalibrationEvalOptions o;
  o.trials = std::getenv("NAO_TEST_QUICK") ? 4 : 12;
  o.seed = 11;
  o.field = FieldDimensions::load(dataPath("config/field_dimensions.json"));
  o.lightings = Lighting::sweep(dataPath("config/lighting.json"));
  const CalibrationEvalResult r = evalCalibration(o);
  EXPECT_EQ(r.trials, o.trials);
  EXPECT_EQ(r.converged, o.trials);
  EXPECT_EQ(r.accepted, o.trials);
  for (int k = 0; k < 6; ++k) {
    EXPECT_LE(r.medianAbsErrorDeg[k], 0.1) << CameraCalibration::kNames[k];
    EXPECT_LE(r.p95AbsErrorDeg[k], 0.25) << CameraCalibration::kNames[k];
  }
  EXPECT_LE(r.solverAgreementMaxDeg, 0.02);
  EXPECT_LE(r.solveSecondsMax, 0.2);
  EXPECT_LE(r.otherSolveSecondsMax, 0.2);
  EXPECT_LE(r.reprojectionMaxPx, 1.0);
  for (const auto& t : r.trialResults) {
    EXPECT_GE(t.run.samples, 6) << "lighting " << t.lighting;
    EXPECT_LT(t.run.reprojectionPx, t.run.reprojectionBeforePx);
  }
}

TEST(CalibrationSim, NoOffsetsStayNearZero) {
  CalibrationRunOptions o;
  o.field = FieldDimensions::load(dataPath("config/field_dimensions.json"));
  o.calibrator.solver = calibration::SolverKind::Ceres;
  const CalibrationRunResult r = runCalibration(o);
  ASSERT_TRUE(r.solution.solver.converged) << r.solution.solver.message;
  EXPECT_TRUE(r.solution.accepted) << r.solution.reason;
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(r.estimate.toArray()[k] / kDeg, 0.0, 0.1) << CameraCalibration::kNames[k];
  EXPECT_LE(r.reprojectionPx, 1.0);
}

// The robot may start on either side line; the left side's goal box side works the same.
TEST(CalibrationSim, LeftStart) {
  CalibrationRunOptions o;
  o.field = FieldDimensions::load(dataPath("config/field_dimensions.json"));
  o.side = 1;
  o.miscalibration = CameraCalibration::fromArray({1 * kDeg, -2 * kDeg, 2.5 * kDeg, 1 * kDeg, -1.5 * kDeg, -2 * kDeg});
  const CalibrationRunResult r = runCalibration(o);
  ASSERT_TRUE(r.solution.accepted) << r.solution.reason;
  for (int k = 0; k < 6; ++k)
    EXPECT_NEAR(r.estimate.toArray()[k] / kDeg, r.truth.toArray()[k] / kDeg, 0.1) << CameraCalibration::kNames[k];
}

}  // namespace
}  // namespace nao::sim
