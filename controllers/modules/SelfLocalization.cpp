#include "controllers/modules/SelfLocalization.h"

#include <cmath>

#include "controllers/modules/ModuleField.h"
#include "perception/modeling/ViewRegion.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

namespace {

NAO_DEBUG_CHANNEL(kLocalization, "localization",
                  "per image: the estimate, every hypothesis (mean, sigma, score) and the filter's counters; skipped images with the reason");

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

void SelfLocalization::applySituation(const GameState& game, const ChallengeMode& challenge) {
  // The game situation decides the field's symmetry: where a robot is put on the field. A
  // challenge start (the calibration challenge's rules) puts it on a side line in line with the
  // own penalty mark, facing into the field: the penalty return's two poses.
  if (challenge.modeId != challengeModeId_) {
    challengeModeId_ = challenge.modeId;
    started_ = true;
    locator_.resetToPenaltyReturn();
    lastImageTime_.reset();  // the robot was carried there
  } else if (!started_) {
    started_ = true;
    if (game.penalised()) locator_.resetToPenaltyReturn();
    else locator_.resetToSidelineEntry(true);
  } else if (wasPenalised_ && !game.penalised()) {
    locator_.resetToPenaltyReturn();
    lastImageTime_.reset();  // the robot was carried: the odometry meanwhile means nothing
  } else if (game.fromGameController && game.state == gc::State::Initial && lastGameState_ != gc::State::Initial) {
    // A new half: the robot was carried to the side line of its half.
    locator_.resetToSidelineEntry(true);
    lastImageTime_.reset();
  }
  wasPenalised_ = game.penalised();
  lastGameState_ = game.state;
}

void SelfLocalization::update() {
  const CameraPercepts& percepts = in<CameraPercepts>();
  const GameState& game = in<GameState>();
  applySituation(game, in<ChallengeMode>());
  RobotPose& pose = out<RobotPose>();
  Pose2 odometry;
  if (game.penalised() || !std::isfinite(percepts.timestamp) ||
      !in<FrameHistory>().odometryAt(percepts.timestamp, odometry)) {
    if (!game.penalised()) {
      ++skippedImages_;
      debug(kLocalization, [&] {
        return nlohmann::json{{"skipped", std::isfinite(percepts.timestamp) ? "no odometry history" : "image time not finite"}};
      });
    }
    const RobotPose last = pose;
    pose = locator_.estimate();
    pose.time = last.time;
    pose.odometry = last.odometry;
    return;
  }
  if (!std::isfinite(odometry.x) || !std::isfinite(odometry.y) || !std::isfinite(odometry.theta)) {
    // A broken odometry reading: no step this image; the next good one steps from the last good.
    ++skippedOdometry_;
    debug(kLocalization, [&] { return nlohmann::json{{"skipped", "odometry not finite"}}; });
  } else {
    if (lastImageTime_ && std::abs(percepts.timestamp - *lastImageTime_) <= params_.maxImageGap)
      if (const auto delta = odometryDelta(lastOdometry_, odometry)) locator_.applyOdometry(*delta);
    lastImageTime_ = percepts.timestamp;
    lastOdometry_ = odometry;
  }

  FieldPercepts field;
  field.time = percepts.timestamp;
  field.lines = percepts.linesPercept();
  field.uncertainty = percepts.camera == CameraId::Top ? params_.top : params_.bottom;
  if (percepts.processed)
    field.view = groundView(percepts.cameraMatrix,
                            percepts.camera == CameraId::Top ? params_.viewDistanceTop : params_.viewDistanceBottom,
                            params_.viewMargin);
  locator_.applyPercepts(field, turnRate(in<FrameHistory>(), percepts.timestamp));
  pose = locator_.estimate();
  // The time and odometry the estimate belongs to (the last good reading's, if this one was not).
  pose.time = lastImageTime_.value_or(percepts.timestamp);
  pose.odometry = lastOdometry_;
  debug(kLocalization, [&] {
    nlohmann::json hyps = nlohmann::json::array();
    for (const auto& h : locator_.hypotheses()) {
      double arc = 0;
      const double expected = locator_.expectedLineLength(h.mean, field.view, &arc);
      hyps.push_back({{"mean", {h.mean.x(), h.mean.y(), h.mean.z()}},
                      {"sigma", {std::sqrt(h.cov(0, 0)), std::sqrt(h.cov(1, 1)), std::sqrt(h.cov(2, 2))}},
                      {"score", h.score},
                      {"age", h.age},
                      {"expected_line_m", expected},
                      {"expected_arc_m", arc}});
    }
    const auto& st = locator_.stats();
    return nlohmann::json{{"camera", cameraName(percepts.camera)},
                          {"pose", {pose.pose.x, pose.pose.y, pose.pose.theta}},
                          {"valid", pose.valid},
                          {"quality", pose.quality},
                          {"sigma_m", pose.sigmaTranslation()},
                          {"hypotheses", hyps},
                          {"lines", percepts.lines.size()},
                          {"circle", percepts.circle.found},
                          {"view", field.view.size()},
                          {"stats", {{"skipped_odometry", st.skippedOdometry}, {"skipped_percepts", st.skippedPercepts},
                                     {"candidates", st.candidates}, {"resets", st.resets},
                                     {"reinitialisations", st.reinitialisations},
                                     {"negative_images", st.negativeImages}, {"off_field", st.offField},
                                     {"prior_violations", st.priorViolations}}}};
  });
}

NAO_REGISTER_MODULE(SelfLocalization);

}  // namespace nao::modules
