#include "controllers/CalibrationLogging.h"

#include "representations/behavior/CalibrationRequest.h"
#include "representations/infrastructure/ChallengeMode.h"
#include "representations/infrastructure/CurrentImage.h"
#include "representations/infrastructure/FrameHistory.h"
#include "robot/Error.h"
#include "robot/ModuleRegistry.h"
#include "robot/OutputFiles.h"

namespace nao {

CalibrationRecorder::CalibrationRecorder(std::string headId, std::string backend) {
  log_.headId = std::move(headId);
  log_.backend = std::move(backend);
}

void CalibrationRecorder::observe(const CameraImage& image, const Blackboard& cognition) {
  if (!cognition.has<CalibrationStatus>() || !cognition.has<FrameHistory>()) return;
  const CalibrationStatus& status = cognition.read<CalibrationStatus>();
  if (status.last.viewId < 0 || status.last.viewId == lastView_ || status.last.imageTime != image.timestamp) return;
  lastView_ = status.last.viewId;
  const int mode = cognition.has<ChallengeMode>() ? cognition.read<ChallengeMode>().modeId : 0;
  if (mode != recordsMode_) {
    log_.records.clear();
    recordsMode_ = mode;
  }
  calibration::CalibrationLogRecord r;
  r.viewId = status.last.viewId;
  r.image = image;
  // What the Calibrator measured the image with: the history at the exposure.
  const FrameHistory& history = cognition.read<FrameHistory>();
  Eigen::Isometry3d robotToTorso;
  history.at(image.timestamp, r.joints, robotToTorso);
  history.imuAngleAt(image.timestamp, r.imuAngle);
  r.accepted = status.last.accepted;
  r.reason = status.last.reason;
  log_.records.push_back(std::move(r));
}

void CalibrationRecorder::write(const std::string& path) const {
  io::writeFile(path, calibration::serializeCalibrationLog(log_));
}

CalibrationReplay replayCalibrationLog(const calibration::CalibrationLog& log, const ModuleContext& context) {
  const std::unique_ptr<ModuleBase> calibrator = createModule("Calibrator", context);
  Blackboard board;
  board.write<CameraCalibration>() = CameraCalibration{};
  board.write<ChallengeMode>() = ChallengeMode{};
  CalibrationReplay replay;
  for (const calibration::CalibrationLogRecord& r : log.records) {
    // The robot held still for the image (the live Calibrator judged it): a still history
    // around the exposure with the recorded joints and IMU angle.
    FrameHistory& history = board.write<FrameHistory>();
    history.entries.clear();
    for (double dt = -0.3; dt <= 0.05; dt += 0.012) {
      FrameHistory::Entry e;
      e.time = r.image.timestamp + dt;
      e.joints = r.joints;
      e.imuAngle = r.imuAngle;
      history.entries.push_back(e);
    }
    board.write<CurrentImage>().image = r.image;
    CalibrationRequest& request = board.write<CalibrationRequest>();
    request = CalibrationRequest{};
    request.action = CalibrationRequest::Action::Collect;
    request.viewId = r.viewId;
    request.camera = r.image.camera;
    calibrator->execute(board);
    const CalibrationStatus& status = board.read<CalibrationStatus>();
    ReplayedView v;
    v.viewId = r.viewId;
    v.camera = r.image.camera;
    v.accepted = status.last.viewId == r.viewId && status.last.accepted;
    v.reason = status.last.viewId == r.viewId ? status.last.reason : "not judged: " + status.last.reason;
    if (v.accepted) v.source = status.last.source;
    v.liveAccepted = r.accepted;
    v.liveReason = r.reason;
    replay.views.push_back(v);
  }
  CalibrationRequest& request = board.write<CalibrationRequest>();
  request = CalibrationRequest{};
  request.action = CalibrationRequest::Action::Solve;
  request.solutionId = board.has<CalibrationStatus>() ? board.read<CalibrationStatus>().solutionId + 1 : 1;
  if (!board.has<FrameHistory>()) board.write<FrameHistory>();
  if (!board.has<CurrentImage>()) board.write<CurrentImage>();
  calibrator->execute(board);
  replay.status = board.read<CalibrationStatus>();
  return replay;
}

}  // namespace nao
