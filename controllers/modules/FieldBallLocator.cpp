#include "controllers/modules/FieldBallLocator.h"

#include <algorithm>
#include <vector>

#include "robot/ModuleRegistry.h"

namespace nao::modules {

namespace {
NAO_DEBUG_CHANNEL(kFieldBalls, "field_balls", "per image: each half's ball estimate (field, m), support and close observations");

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const std::size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(m), v.end());
  const double upper = v[m];
  if (v.size() % 2) return upper;
  return (upper + *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(m))) / 2;
}

Eigen::Vector2d median2(const std::vector<Eigen::Vector2d>& points) {
  std::vector<double> xs, ys;
  for (const Eigen::Vector2d& p : points) {
    xs.push_back(p.x());
    ys.push_back(p.y());
  }
  return {median(xs), median(ys)};
}

nlohmann::json ballJson(const FieldBalls::Ball& b) {
  return {{"seen", b.seen}, {"position", {b.position.x(), b.position.y()}}, {"support", b.support},
          {"close", b.close}, {"close_position", {b.closePosition.x(), b.closePosition.y()}},
          {"close_spread", b.closeSpread}};
}
}  // namespace

FieldBallLocator::FieldBallLocator(const ModuleContext& context) : params_(context.load<Params>(name())) {}

FieldBalls::Ball FieldBallLocator::estimate(const std::deque<Observation>& obs, const Params& params) {
  FieldBalls::Ball ball;
  if (obs.empty()) return ball;
  const double r2 = params.clusterRadius * params.clusterRadius;
  // The densest spot: the observation with the most others near it (the newer wins a tie).
  std::size_t best = 0;
  int bestCount = -1;
  for (std::size_t i = 0; i < obs.size(); ++i) {
    int count = 0;
    for (const Observation& o : obs) count += (o.field - obs[i].field).squaredNorm() <= r2;
    if (count >= bestCount) {
      bestCount = count;
      best = i;
    }
  }
  std::vector<Eigen::Vector2d> members, close;
  double lastSeen = -1;
  // Newest first, so that the close median takes the newest closeSamples.
  for (auto it = obs.rbegin(); it != obs.rend(); ++it) {
    if ((it->field - obs[best].field).squaredNorm() > r2) continue;
    members.push_back(it->field);
    lastSeen = std::max(lastSeen, it->time);
    if (it->distance <= params.closeDistance) ++ball.close;
    if (it->distance <= params.closeDistance && static_cast<int>(close.size()) < params.closeSamples)
      close.push_back(it->field);
  }
  ball.support = static_cast<int>(members.size());
  ball.seen = ball.support >= params.minSupport;
  ball.position = median2(members);
  ball.lastSeen = lastSeen;
  if (!close.empty()) {
    ball.closePosition = median2(close);
    std::vector<double> d;
    for (const Eigen::Vector2d& p : close) d.push_back((p - ball.closePosition).norm());
    ball.closeSpread = median(d);
  }
  return ball;
}

void FieldBallLocator::update() {
  FieldBalls& balls = out<FieldBalls>();
  const ChallengeMode& mode = in<ChallengeMode>();
  if (mode.modeId != modeId_) {
    // The referee placed the robot and the balls anew.
    modeId_ = mode.modeId;
    own_.clear();
    opponent_.clear();
    ++resets_;
  }
  const CameraPercepts& percepts = in<CameraPercepts>();
  const RobotPose& pose = in<RobotPose>();
  const BallPercept& b = percepts.ball;
  const double distance = b.position.norm();
  if (percepts.processed && b.seen && pose.valid && pose.sigmaTranslation() <= params_.maxPoseSigma &&
      distance <= params_.maxDistance) {
    const Eigen::Vector2d field = pose.pose * b.position;
    std::deque<Observation>& half = field.x() < 0 ? own_ : opponent_;
    half.push_back({field, distance, percepts.timestamp});
    while (static_cast<int>(half.size()) > params_.keep) half.pop_front();
  }
  for (std::deque<Observation>* half : {&own_, &opponent_})
    while (!half->empty() && half->front().time < percepts.timestamp - params_.maxAge) half->pop_front();
  balls.own = estimate(own_, params_);
  balls.opponent = estimate(opponent_, params_);
  balls.resets = resets_;
  debug(kFieldBalls, [&] { return nlohmann::json{{"own", ballJson(balls.own)}, {"opponent", ballJson(balls.opponent)}}; });
}

NAO_REGISTER_MODULE(FieldBallLocator);

}  // namespace nao::modules
