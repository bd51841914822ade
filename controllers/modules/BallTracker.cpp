#include "controllers/modules/BallTracker.h"

#include <algorithm>
#include <cmath>

#include "controllers/modules/ModuleField.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

namespace {

NAO_DEBUG_CHANNEL(kBallTracks, "ball_tracks", "per image: every ball track (id, field position, sightings, misses) and what the image's percept did");

constexpr double kBallRadius = 0.05;  // m

BallTracks::Track expected(int id, const Eigen::Vector2d& at) {
  BallTracks::Track t;
  t.id = id;
  t.position = at;
  return t;
}

}  // namespace

BallTracker::BallTracker(const ModuleContext& context) : params_(context.load<Params>(name())), field_(fieldFor(context)) {}

void BallTracker::update() {
  auto& tracks = out<BallTracks>().tracks;
  const CameraPercepts& percepts = in<CameraPercepts>();
  const RobotPose& pose = in<RobotPose>();
  const GameState& game = in<GameState>();
  const double x = field_.length / 2 - field_.goalBoxAreaLength, y = field_.goalBoxAreaWidth / 2;
  const Eigen::Vector2d starts[] = {{-x, -y}, {-x, y}, {x, -y}, {x, y}};
  // SET: the referee has put the balls on the goal free-kick positions.
  if (game.fromGameController && game.state == gc::State::Set && lastState_ != gc::State::Set) {
    tracks.clear();
    for (const Eigen::Vector2d& s : starts) tracks.push_back(expected(nextId_++, s));
  }
  lastState_ = game.state;
  // A point of ours: the referee returns that ball to the own start point farthest from us.
  if (game.ownScore > lastOwnScore_ && pose.valid) {
    const Eigen::Vector2d robot(pose.pose.x, pose.pose.y);
    const Eigen::Vector2d& a = starts[0];
    const Eigen::Vector2d& b = starts[1];
    const Eigen::Vector2d at = (a - robot).norm() > (b - robot).norm() ? a : b;
    const bool known = std::any_of(tracks.begin(), tracks.end(), [&](const auto& t) { return (t.position - at).norm() < 0.5; });
    if (!known) tracks.push_back(expected(nextId_++, at));
  }
  lastOwnScore_ = game.ownScore;
  if (!percepts.processed || !pose.valid || pose.sigmaTranslation() > params_.maxPoseSigma) return;

  // The percept, in the field.
  int took = -1;
  const BallPercept& b = percepts.ball;
  if (b.seen && b.position.allFinite() && b.position.norm() <= params_.maxDistance) {
    const Eigen::Vector2d seen = pose.pose * b.position;
    // A ball off the field is not in play (the referee's spare balls lie there).
    const bool onField = std::abs(seen.x()) <= field_.length / 2 + params_.fieldMargin &&
                         std::abs(seen.y()) <= field_.width / 2 + params_.fieldMargin;
    const double reach = params_.associate + params_.associatePerMetre * b.position.norm();
    double best = reach;
    for (std::size_t i = 0; i < tracks.size(); ++i)
      if (const double d = (tracks[i].position - seen).norm(); d < best) best = d, took = static_cast<int>(i);
    if (took < 0 && onField && static_cast<int>(tracks.size()) < params_.maxTracks) {
      tracks.push_back(expected(nextId_++, seen));
      took = static_cast<int>(tracks.size()) - 1;
      tracks.back().sightings = 0;
    }
    if (took >= 0) {
      BallTracks::Track& t = tracks[static_cast<std::size_t>(took)];
      // Smoothed against jitter; a ball that moved (rolling, pushed) is taken where it is now.
      const bool moved = (seen - t.position).norm() > params_.jitter;
      t.position = t.sightings == 0 || moved ? seen : (1 - params_.smoothing) * t.position + params_.smoothing * seen;
      ++t.sightings;
      t.misses = 0;
      t.lastSeen = percepts.timestamp;
    }
  }
  // The vision reports one ball per image, the best it sees (mostly the nearest): a track this
  // image should have shown counts a miss when no ball was reported, or only one clearly
  // farther away (a track left behind by a ball that rolled off).
  const int tookId = took >= 0 ? tracks[static_cast<std::size_t>(took)].id : -1;
  const CameraMatrix& m = percepts.cameraMatrix;
  const double expect = percepts.camera == CameraId::Top ? params_.expectTop : params_.expectBottom;
  const double mx = params_.imageMargin * m.intrinsics.width, my = params_.imageMargin * m.intrinsics.height;
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    const Eigen::Vector2d rel = pose.pose.inverse() * tracks[i].position;
    if (rel.norm() > expect || (b.seen && b.position.norm() < rel.norm() + params_.fartherBy)) continue;
    const auto px = m.project(Eigen::Vector3d(rel.x(), rel.y(), kBallRadius));
    if (px && px->x() >= mx && px->y() >= my && px->x() < m.intrinsics.width - mx && px->y() < m.intrinsics.height - my)
      ++tracks[i].misses;
  }
  tracks.erase(std::remove_if(tracks.begin(), tracks.end(), [&](const auto& t) { return t.misses >= params_.maxMisses; }),
               tracks.end());
  debug(kBallTracks, [&] {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& t : tracks)
      list.push_back({{"id", t.id}, {"field", {t.position.x(), t.position.y()}}, {"sightings", t.sightings}, {"misses", t.misses}});
    return nlohmann::json{{"camera", cameraName(percepts.camera)}, {"tracks", list}, {"took", tookId}};
  });
}

NAO_REGISTER_MODULE(BallTracker);

}  // namespace nao::modules
