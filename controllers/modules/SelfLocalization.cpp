#include "controllers/modules/SelfLocalization.h"

#include <cmath>

#include "controllers/modules/ModuleField.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

namespace {

// The body's turn rate at time t from the odometry (rad/s): feature resets are refused while
// it turns fast (the image is smeared and its time uncertain).
double turnRate(const FrameHistory& history, double t) {
  constexpr double kSpan = 0.05;  // s
  Pose2 a, b;
  if (!history.odometryAt(t - kSpan, a) || !history.odometryAt(t, b)) return 0;
  return Pose2::wrap(b.theta - a.theta) / kSpan;
}

}  // namespace

SelfLocalization::SelfLocalization(const ModuleContext& context)
    : params_(context.load<Params>(name())), locator_(FieldModel::from(fieldFor(context)), params_.filter) {}

void SelfLocalization::applySituation(const GameState& game) {
  // The game situation decides the field's symmetry: where a robot is put on the field.
  if (!started_) {
    started_ = true;
    if (game.penalised()) locator_.resetToPenaltyReturn();
    else locator_.resetToSidelineEntry(true);
  } else if (wasPenalised_ && !game.penalised()) {
    locator_.resetToPenaltyReturn();
    lastImageTime_.reset();  // the robot was carried: the odometry meanwhile means nothing
  }
  wasPenalised_ = game.penalised();
}

void SelfLocalization::update() {
  const CameraPercepts& percepts = in<CameraPercepts>();
  const GameState& game = in<GameState>();
  applySituation(game);
  RobotPose& pose = out<RobotPose>();
  Pose2 odometry;
  if (game.penalised() || !std::isfinite(percepts.timestamp) ||
      !in<FrameHistory>().odometryAt(percepts.timestamp, odometry)) {
    if (!game.penalised()) ++skippedImages_;
    const RobotPose last = pose;
    pose = locator_.estimate();
    pose.time = last.time;
    pose.odometry = last.odometry;
    return;
  }
  if (lastImageTime_ && std::abs(percepts.timestamp - *lastImageTime_) <= params_.maxImageGap)
    if (const auto delta = odometryDelta(lastOdometry_, odometry)) locator_.applyOdometry(*delta);
  lastImageTime_ = percepts.timestamp;
  lastOdometry_ = odometry;

  FieldPercepts field;
  field.time = percepts.timestamp;
  field.lines = percepts.linesPercept();
  field.uncertainty = percepts.camera == CameraId::Top ? params_.top : params_.bottom;
  locator_.applyPercepts(field, turnRate(in<FrameHistory>(), percepts.timestamp));
  pose = locator_.estimate();
  pose.time = percepts.timestamp;
  pose.odometry = odometry;
}

NAO_REGISTER_MODULE(SelfLocalization);

}  // namespace nao::modules
