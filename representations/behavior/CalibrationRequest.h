#pragma once
// What the calibration behaviour asks the calibrator (Calibrator, cognition) to do with the
// images that come: take a sample of the goal box for a view, solve, apply a solution, verify it.
#include "robot/CameraImage.h"

namespace nao {

struct CalibrationRequest {
  enum class Action { Idle, Collect, Solve, Apply, Verify, Reset };
  Action action = Action::Idle;
  int viewId = 0;                  // Collect, Verify: the view; one sample (or check) per id
  CameraId camera = CameraId::Top;  // Collect, Verify: the camera to take it with
  int solutionId = 0;              // Solve: the solve wanted (a new id solves again); Apply: which one
};

inline const char* calibrationActionName(CalibrationRequest::Action a) {
  switch (a) {
    case CalibrationRequest::Action::Idle: return "idle";
    case CalibrationRequest::Action::Collect: return "collect";
    case CalibrationRequest::Action::Solve: return "solve";
    case CalibrationRequest::Action::Apply: return "apply";
    case CalibrationRequest::Action::Verify: return "verify";
    case CalibrationRequest::Action::Reset: return "reset";
  }
  return "?";
}

}  // namespace nao
