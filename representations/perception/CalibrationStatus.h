#pragma once
// What the calibrator (cognition) has done: the samples it took per camera, the last view's
// verdict, its solution and whether it was applied. The calibration behaviour reads it (as
// Previous<CalibrationStatus>); CameraCalibrationProvider (motion) adopts `applied` when
// `appliedId` changes, so every camera matrix from then on uses the new offsets.
#include <array>
#include <optional>
#include <string>

#include "perception/CameraCalibration.h"
#include "perception/calibration/Calibrator.h"

namespace nao {

struct CalibrationStatus {
  std::array<int, 2> samples{};  // per camera (top, bottom), accepted
  struct ViewResult {
    int viewId = -1;  // the request's view; -1: none yet
    bool accepted = false;
    std::string reason;  // why not
    double imageTime = 0;
    double extractMs = 0;  // wall time from image to sample or verdict (diagnostics)
    std::string source;    // where the sample's segments came from: lsd or vision
  } last;
  int solutionId = 0;  // counts the solves
  CameraCalibration offsets;  // the last solution
  bool converged = false, accepted = false;
  double rmsAngleDeg = 0, rmsDepthM = 0;
  std::string reason;  // why the last solution is not accepted
  int appliedId = 0;   // a new id: CameraCalibrationProvider switches to `applied`
  CameraCalibration applied;
  double verifyAngleDeg = -1;  // the check after applying; -1: not verified
  calibration::CalibrationSolution solution;  // the last solve in full (samples used, dropped, residuals)
  std::optional<calibration::SolverResult> otherSolver;  // Calibrator.compareSolvers: the other solver, same samples
};

}  // namespace nao
