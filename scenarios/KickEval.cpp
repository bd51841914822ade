#include "scenarios/KickEval.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "perception/Geometry.h"
#include "robot/Error.h"
#include "scenarios/SimRun.h"
#include "sim/SceneBuilder.h"
#include "sim/World.h"

namespace nao::sim {

KickTrialResult runKick(const KickTrialOptions& o) {
  MotionSimOptions so;
  so.seed = o.seed;
  so.randomize = o.randomize;
  so.variation = o.variation;
  so.params = o.params;
  so.pose = Eigen::Vector3d(-2.0, 0, 0);
  so.balls = {Eigen::Vector3d(so.pose.x() + o.ballDistance * std::cos(o.ballBearing),
                              so.pose.y() + o.ballDistance * std::sin(o.ballBearing), kBallRadius)};
  MotionSim sim(so);
  KickTrialResult r;
  r.variation = sim.variation();
  const double goal = so.pose.z() + o.direction;  // field frame
  MotionRequest stand;
  for (int i = 0; i < static_cast<int>(std::lround((o.params.transitionTime + 0.5) / kCycleTime)); ++i)
    if (!sim.cycle(stand)) throw Error("simulation", sim.stopReason());
  const Eigen::Vector3d ballStart = sim.world().ballPosition(0);
  const double start = sim.time();
  MotionRequest kick;
  kick.motion = MotionType::Kick;
  kick.kickId = 1;
  bool wasDown = false, first = true;
  double restSince = -1;
  while (sim.time() - start < o.timeLimit + 15) {
    // The ball percept: its true position in the robot frame; the direction likewise.
    const Eigen::Vector3d pose = sim.truePose();
    kick.ballPosition = fieldToRobot(sim.world().ballPosition(0).head<2>(), pose);
    kick.kickDirection = Pose2::wrap(goal - pose.z());
    if (first) r.leftFoot = kick.ballPosition.y() >= 0;  // the motion engine picks the foot likewise
    first = false;
    const bool kicking = !r.kicked && sim.time() - start < o.timeLimit;
    if (!sim.cycle(kicking ? kick : stand)) throw Error("simulation", sim.stopReason());
    if (!r.kicked && sim.info().kickDone) {
      r.kicked = true;
      r.time = sim.time() - start;
    }
    const bool down = sim.trueFallen();
    if (down && !wasDown) ++r.falls;
    wasDown = down;
    const double speed = sim.world().ballVelocity(0).head<2>().norm();
    r.ballSpeed = std::max(r.ballSpeed, speed);
    if ((r.kicked || sim.time() - start >= o.timeLimit) && speed < 0.01) {
      if (restSince < 0) restSince = sim.time();
      if (sim.time() - restSince > 0.5) break;
    } else {
      restSince = -1;
    }
  }
  const Eigen::Vector2d moved = (sim.world().ballPosition(0) - ballStart).head<2>();
  r.travel = moved.norm();
  r.directionErrorSigned = r.travel > 0.05 ? Pose2::wrap(std::atan2(moved.y(), moved.x()) - goal) : M_PI;
  r.directionError = std::abs(r.directionErrorSigned);
  return r;
}

KickEvalResult evalKick(const KickEvalOptions& o) {
  if (o.trials < 1) throw Error("--trials", "must be at least 1");
  KickEvalResult result;
  std::vector<double> travel, error;
  for (int t = 0; t < o.trials; ++t) {
    const std::uint64_t seed = o.seed * 15485863ULL + static_cast<std::uint64_t>(t);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> dist(0.3, 0.8), angle(-M_PI / 4, M_PI / 4);
    KickTrialOptions k;
    k.ballDistance = dist(rng);
    k.ballBearing = angle(rng);
    k.direction = angle(rng);
    k.seed = seed;
    k.randomize = o.randomize;
    k.variation = o.variation;
    k.params = o.params;
    const KickTrialResult r = runKick(k);
    result.falls += r.falls;
    result.kicked += r.kicked;
    travel.push_back(r.travel);
    error.push_back(r.directionError);
    result.trials.push_back(r);
    if (o.progress) o.progress(t + 1, o.trials);
  }
  result.travelMedian = median(travel);
  result.directionErrorMedian = median(error);
  return result;
}

}  // namespace nao::sim
