#pragma once
// The calibration log (perception/calibration/CalibrationLog.h) around the robot program:
// CalibrationRecorder watches the cognition runs (RobotProgram::CognitionObserver) and keeps
// every image the Calibrator judged for a view, with the joints and IMU angle the Calibrator
// measured it with (FrameHistory at the exposure); replayCalibrationLog runs the robot
// program's own Calibrator module on those images and solves, without a simulator.
#include <string>
#include <vector>

#include "perception/calibration/CalibrationLog.h"
#include "representations/perception/CalibrationStatus.h"
#include "robot/Blackboard.h"
#include "robot/Parameters.h"

namespace nao {

class CalibrationRecorder {
 public:
  CalibrationRecorder(std::string headId, std::string backend);
  // After each cognition run: a view the Calibrator judged on this image becomes a record. A
  // new challenge start (ChallengeMode::modeId) that collects again starts the log over, as the
  // Calibrator forgets its samples then.
  void observe(const CameraImage& image, const Blackboard& cognition);
  const calibration::CalibrationLog& log() const { return log_; }
  // Writes the log whole (robot/OutputFiles.h: nothing half-written).
  void write(const std::string& path) const;

 private:
  calibration::CalibrationLog log_;
  int lastView_ = -1;
  int recordsMode_ = -1;
};

struct ReplayedView {
  int viewId = 0;
  CameraId camera = CameraId::Top;
  bool accepted = false, liveAccepted = false;
  std::string reason, liveReason;
  std::string source;  // where an accepted sample's segments came from (ExtractionResult::source)
};

struct CalibrationReplay {
  std::vector<ReplayedView> views;
  CalibrationStatus status;  // after the solve: offsets, accepted, residuals, samples
};

// The log's images through a Calibrator made from `context` (its parameters, the field), each
// as the view it was recorded for, then one solve.
CalibrationReplay replayCalibrationLog(const calibration::CalibrationLog& log, const ModuleContext& context);

}  // namespace nao
