#pragma once
// The autonomous extrinsic camera calibration in the simulator, scored against the injected
// truth. The robot starts at the challenge's initial position (side line, in line with the own
// penalty mark), goes to the calibration position at the side of its goal box and takes the
// box with each camera at several head pan angles, turning its body so the box stays in view;
// the head is held still while each image is taken. The samples (refined image lines, joint
// angles, IMU angles) are solved for the six offsets, and the result is compared with the
// offsets the simulator injected.
//
// TO BE REPLACED BY WALKING: the robot is teleported (World::placeRobot) to the calibration
// position and turned in place between views; the walk (issue 4) will do this. The robot does
// not need to know where it stands exactly (only relative angles and distances enter the
// cost), which is why `placementError` may put it up to 10 cm / 5 deg off the planned pose.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "perception/CameraCalibration.h"
#include "perception/FieldDimensions.h"
#include "perception/calibration/Calibrator.h"
#include "perception/calibration/CalibrationViews.h"
#include "perception/calibration/SampleExtraction.h"
#include "sim/Lighting.h"

namespace nao::sim {

struct CalibrationRunOptions {
  FieldDimensions field;
  std::string robotModel;                 // empty: models/nao_v6.xml
  CameraCalibration miscalibration;       // injected into the simulated hardware
  Lighting lighting;
  int side = -1;                          // start on the right (-1, y < 0) or left (+1) side line
  Eigen::Vector3d placementError = Eigen::Vector3d::Zero();  // true minus planned pose (m, m, rad)
  calibration::ViewPlanOptions views;
  calibration::CalibratorOptions calibrator;  // cost options are set from the field
  calibration::LineSource lineSource = calibration::LineSource::Lsd;
  bool compareSolvers = false;            // also solve the same samples with the other solver
  std::uint64_t seed = 1;
  std::string imagesDir;                  // non-empty: every view annotated, and the Fig. 2 pictures
  double settleSeconds = 0.3;             // simulated time to let the robot come to rest per view
};

struct ViewRecord {
  CameraId camera = CameraId::Top;
  double headYawDeg = 0, headPitchDeg = 0;
  bool accepted = false;
  std::string reason;                     // why rejected
  std::optional<calibration::SampleResiduals> residuals;  // at the estimate, when used in the solve
  double extractMs = 0;                   // wall time from image to sample (or rejection)
  std::string source;                     // where the sample's segments came from: vision or lsd
};

struct CalibrationRunResult {
  std::string headId;                     // the simulated robot's head id (the calibration store's key)
  CameraCalibration truth, estimate;
  calibration::CalibrationSolution solution;
  std::optional<calibration::SolverResult> otherSolver;  // the other solver, same samples, no outlier step
  std::vector<ViewRecord> views;
  int samples = 0;
  std::vector<calibration::CalibrationSample> sampleData;  // what the solver got (before outliers)
  // Field lines in every accepted view: RMS pixel distance between where the camera model
  // puts them (with the estimate / with no offsets, at the true robot pose) and where they
  // truly are in the image (the simulator's camera pose).
  double reprojectionPx = 0, reprojectionBeforePx = 0;
  int reprojectionPoints = 0;
  double wallSeconds = 0;
  std::vector<std::string> imagesWritten;
};

// With too few samples the solution is not converged and says why (views hold the reasons).
CalibrationRunResult runCalibration(const CalibrationRunOptions& options);

struct CalibrationEvalOptions {
  int trials = 100;
  std::uint64_t seed = 1;
  FieldDimensions field;
  std::string robotModel;
  std::vector<Lighting> lightings;        // one is drawn per trial
  double maxOffsetDeg = 3;                // injected offsets uniform in +-this, per parameter
  double maxPlacementError = 0.10;        // m, per axis... within a disc of this radius
  double maxHeadingErrorDeg = 5;
  calibration::SolverKind solver = calibration::SolverKind::GaussNewton;
  calibration::ViewPlanOptions views;       // the views each trial takes
  calibration::CostOptions cost;            // residual weights and extras (goal box depth from the field)
  calibration::LineSource lineSource = calibration::LineSource::Lsd;
  std::function<void(int done, int total)> progress;
};

struct CalibrationTrial {
  CalibrationRunResult run;
  std::string lighting;
  Eigen::Vector3d placementError = Eigen::Vector3d::Zero();
};

struct CalibrationEvalResult {
  int trials = 0, converged = 0, accepted = 0;
  std::array<double, 6> medianAbsErrorDeg{}, p95AbsErrorDeg{}, maxAbsErrorDeg{};
  double reprojectionMedianPx = 0, reprojectionP95Px = 0, reprojectionMaxPx = 0;
  double solverAgreementMaxDeg = 0;        // largest |GN - Ceres| over all trials and parameters
  double solveSecondsMax = 0, otherSolveSecondsMax = 0, solveSecondsMedian = 0;
  std::vector<CalibrationTrial> trialResults;
};

CalibrationEvalResult evalCalibration(const CalibrationEvalOptions& options);

// Quantile q (0..1) by nearest rank of the sorted values; 0 for none.
double quantile(std::vector<double> values, double q);

}  // namespace nao::sim
