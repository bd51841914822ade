#include "controllers/modules/BallLocator.h"

#include <cmath>

#include "robot/ModuleRegistry.h"

namespace nao::modules {

namespace {
constexpr double kBallRadius = 0.05;  // m
NAO_DEBUG_CHANNEL(kBallModel, "ball_model", "per image: the percept, whether the ball was expected in view, the model and its hypotheses");
}

BallLocator::BallLocator(const ModuleContext& context)
    : params_(context.load<Params>(name())), filter_(params_.filter) {}

bool BallLocator::expectedInView(const Eigen::Vector2d& ball, const CameraPercepts& percepts, const Params& params) {
  const double maxDistance =
      percepts.camera == CameraId::Top ? params.maxExpectedDistanceTop : params.maxExpectedDistanceBottom;
  if (!ball.allFinite() || ball.norm() > maxDistance) return false;
  const CameraMatrix& m = percepts.cameraMatrix;
  const auto pixel = m.project(Eigen::Vector3d(ball.x(), ball.y(), kBallRadius));
  if (!pixel) return false;
  const double mx = params.imageMargin * m.intrinsics.width, my = params.imageMargin * m.intrinsics.height;
  return pixel->x() >= mx && pixel->y() >= my && pixel->x() < m.intrinsics.width - mx &&
         pixel->y() < m.intrinsics.height - my;
}

void BallLocator::update() {
  const CameraPercepts& percepts = in<CameraPercepts>();
  BallInput input;
  input.time = percepts.timestamp;
  Pose2 odometry;
  if (in<FrameHistory>().odometryAt(percepts.timestamp, odometry)) {
    if (lastImageTime_ && std::abs(percepts.timestamp - *lastImageTime_) <= params_.maxImageGap)
      if (const auto delta = odometryDelta(lastOdometry_, odometry)) input.odometryDelta = *delta;
    lastImageTime_ = percepts.timestamp;
    lastOdometry_ = odometry;
  }
  if (percepts.ball.seen) input.observations.push_back({percepts.ball.position, percepts.ball.covariance});
  // Expected in view: where the model will be after this cycle's odometry (the filter applies
  // it before the percepts), in this image.
  const BallModel& before = filter_.model();
  if (before.valid && !before.lost) {
    const Eigen::Vector2d predicted = input.odometryDelta.inverse() * before.position;
    input.ballExpectedInView = percepts.processed && expectedInView(predicted, percepts, params_);
  }
  const RobotPose& pose = in<RobotPose>();
  if (pose.valid) input.robotPose = pose.pose;
  const BallModel& model = out<BallModel>() = filter_.update(input);
  debug(kBallModel, [&] {
    nlohmann::json hyps = nlohmann::json::array();
    for (const auto& h : filter_.hypotheses())
      hyps.push_back({{"rolling", h.rolling}, {"x", {h.x[0], h.x[1], h.x[2], h.x[3]}}, {"measurements", h.measurements}});
    return nlohmann::json{{"camera", cameraName(percepts.camera)},
                          {"percept", percepts.ball.seen ? nlohmann::json{percepts.ball.position.x(), percepts.ball.position.y()}
                                                         : nlohmann::json()},
                          {"expected_in_view", input.ballExpectedInView},
                          {"valid", model.valid},
                          {"lost", model.lost},
                          {"rolling", model.rolling},
                          {"position", {model.position.x(), model.position.y()}},
                          {"velocity", {model.velocity.x(), model.velocity.y()}},
                          {"end", {model.endPosition.x(), model.endPosition.y()}},
                          {"hypotheses", hyps}};
  });
}

NAO_REGISTER_MODULE(BallLocator);

}  // namespace nao::modules
