#include "scenarios/WalkEval.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "perception/Geometry.h"
#include "robot/Error.h"
#include "scenarios/SimRun.h"
#include "sim/SimBackend.h"
#include "sim/World.h"

namespace nao::sim {

NAO_DEBUG_CHANNEL(kWalkFalls, "walk_falls",
                  "eval walk: each fall, with the trial, the seconds into the trial and into the command, the "
                  "commanded and the applied speed (m/s, deg/s)");

namespace {

constexpr double kWarmup = 1.0;  // s standing before a walk starts

double unwrapStep(double& last, double now) {
  const double d = Pose2::wrap(now - last);
  last = now;
  return d;
}

// Ground-truth pose of the robot frame relative to a start pose.
Eigen::Vector3d relativeTo(const Eigen::Vector3d& start, const Eigen::Vector3d& now) {
  const Eigen::Vector2d xy = fieldToRobot(now.head<2>(), start);
  return {xy.x(), xy.y(), Pose2::wrap(now.z() - start.z())};
}

}  // namespace

FieldDimensions motionField() {
  FieldDimensions d;
  d.length = 24;
  d.width = 16;
  d.validate("motion field");
  return d;
}

AppliedVariation applyVariation(World& world, int robot, const RobotVariation& v, std::uint64_t seed) {
  std::mt19937_64 rng(seed ^ 0x5bd1e995ULL);
  AppliedVariation out;
  out.randomized = true;
  out.totalMass = world.scaleLinkMasses(robot, v.massSpread, rng());
  JointArray offsets{};
  std::uniform_real_distribution<double> offset(-v.jointOffset, v.jointOffset);
  for (int j = 0; j < NumJoints; ++j) {
    offsets[j] = (j == LHand || j == RHand) ? 0.0 : offset(rng);
    out.maxJointOffset = std::max(out.maxJointOffset, std::abs(offsets[j]));
  }
  world.setJointOffsets(robot, offsets);
  out.jointOffsets = offsets;
  out.friction = std::uniform_real_distribution<double>(v.frictionMin, v.frictionMax)(rng);
  world.setFloorFriction(out.friction);
  return out;
}

MotionSim::MotionSim(const MotionSimOptions& o) : walkLimits_(o.params.walk) {
  SceneSpec spec;
  spec.field = o.field;
  spec.robots = {o.pose};
  spec.balls = o.balls;
  world_ = std::make_unique<World>(spec, o.seed);
  if (o.randomize) variation_ = applyVariation(*world_, 0, o.variation, o.seed);
  JointArray posture = walkLimits_.standPosture();
  if (!o.posture.empty()) {
    if (o.posture.size() != NumJoints) throw Error("posture", "needs one angle per joint");
    std::copy(o.posture.begin(), o.posture.end(), posture.begin());
  }
  world_->placeRobot(0, o.pose, posture);
  backend_ = std::make_unique<SimBackend>(*world_, 0, true);
  RobotProgramConfig config;
  config.motion = o.params;
  config.withoutBehavior();  // this scenario's MotionRequest drives the walk
  config.debug = o.debug;
  program_ = std::make_unique<RobotProgram>(config);
}

MotionSim::~MotionSim() = default;

bool MotionSim::cycle(const MotionRequest& request, const HeadMotionRequest& head) {
  program_->blackboard().write<MotionRequest>() = request;
  program_->blackboard().write<HeadMotionRequest>() = head;
  return program_->cycle(*backend_);
}

const SensorFrame& MotionSim::frame() const { return program_->blackboard().read<SensorFrame>(); }
const FallState& MotionSim::fallState() const { return program_->blackboard().read<FallState>(); }
const MotionInfo& MotionSim::info() const { return program_->blackboard().read<MotionInfo>(); }
const Odometry& MotionSim::odometry() const { return program_->blackboard().read<Odometry>(); }

double MotionSim::time() const { return world_->time(); }
Eigen::Vector3d MotionSim::truePose() const { return world_->robotPose(0); }
double MotionSim::trueTilt() const {
  return std::acos(std::clamp(world_->torsoPose(0).linear()(2, 2), -1.0, 1.0));
}
std::string MotionSim::stopReason() const { return backend_->stopReason(); }

namespace {

// Tracks a trial's ground truth: the unwrapped pose relative to the start, the path length
// sampled every 0.5 s (the sway within a step does not count), falls, tilt.
struct TruthTracker {
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Pose2 odometryStart;
  double lastYaw = 0, turned = 0;
  Eigen::Vector2d lastSample = Eigen::Vector2d::Zero();
  double nextSample = 0, distance = 0, maxTilt = 0;
  int falls = 0;
  bool wasDown = false;

  void begin(MotionSim& sim) {
    start = sim.truePose();
    odometryStart = sim.odometry().pose;
    lastYaw = start.z();
    turned = 0;
    lastSample = start.head<2>();
    nextSample = sim.time() + 0.5;
    distance = 0;
  }
  void update(MotionSim& sim) {
    const Eigen::Vector3d p = sim.truePose();
    turned += unwrapStep(lastYaw, p.z());
    if (sim.time() >= nextSample) {
      distance += (p.head<2>() - lastSample).norm();
      lastSample = p.head<2>();
      nextSample += 0.5;
    }
    const double tilt = sim.trueTilt();
    maxTilt = std::max(maxTilt, tilt);
    const bool down = sim.trueFallen();
    if (down && !wasDown) ++falls;
    wasDown = down;
  }
  // Odometry's displacement since begin(), in the start robot frame, against the truth.
  void finish(MotionSim& sim, WalkRunResult& r) {
    const Eigen::Vector3d p = sim.truePose();
    distance += (p.head<2>() - lastSample).norm();
    const Eigen::Vector3d truth = relativeTo(start, p);
    const Pose2 odo = odometryStart.inverse() * sim.odometry().pose;
    r.distance = distance;
    r.displacement = truth.head<2>();
    r.turned = turned;
    r.odometryError = (Eigen::Vector2d(odo.x, odo.y) - truth.head<2>()).norm();
    r.odometryErrorRatio = distance > 0.05 ? r.odometryError / distance : 0.0;
    r.odometryAngleError = std::abs(Pose2::wrap(odo.theta - truth.z()));
    r.falls = falls;
    r.maxTilt = maxTilt;
  }
};

}  // namespace

WalkRunResult runWalk(const WalkRunOptions& o) {
  MotionSimOptions so;
  so.field = o.field;
  so.seed = o.seed;
  so.randomize = o.randomize;
  so.variation = o.variation;
  so.params = o.params;
  so.debug = o.debug;
  MotionSim sim(so);
  MotionRequest stand;
  const int warm = static_cast<int>(std::lround((so.params.transitionTime + kWarmup) / kCycleTime));
  for (int i = 0; i < warm; ++i)
    if (!sim.cycle(stand)) throw Error("simulation", sim.stopReason());
  TruthTracker track;
  track.begin(sim);
  MotionRequest walk;
  walk.motion = MotionType::Walk;
  walk.walkSpeed = o.speed;
  const int cycles = static_cast<int>(std::lround(o.seconds / kCycleTime));
  for (int i = 0; i < cycles && !track.falls; ++i) {
    if (!sim.cycle(walk)) throw Error("simulation", sim.stopReason());
    track.update(sim);
  }
  WalkRunResult r;
  r.seconds = o.seconds;
  const Eigen::Vector3d atEnd = relativeTo(track.start, sim.truePose());
  // Then stop and stand; odometry and distance count the stop too.
  for (int i = 0; i < static_cast<int>(2.0 / kCycleTime) && !track.falls; ++i) {
    if (!sim.cycle(stand)) throw Error("simulation", sim.stopReason());
    track.update(sim);
  }
  track.finish(sim, r);
  r.forwardSpeed = atEnd.x() / o.seconds;
  r.sidewaysSpeed = atEnd.y() / o.seconds;
  r.meanSpeed = atEnd.head<2>().norm() / o.seconds;
  r.turnRate = track.turned / o.seconds;  // includes the stop's little turn, negligible
  r.variation = sim.variation();
  return r;
}

WalkEvalResult evalWalk(const WalkEvalOptions& o) {
  if (o.trials < 1) throw Error("--trials", "must be at least 1");
  WalkEvalResult result;
  std::vector<double> ratios;
  for (int t = 0; t < o.trials; ++t) {
    const std::uint64_t seed = o.seed * 1000003ULL + static_cast<std::uint64_t>(t);
    std::mt19937_64 rng(seed);
    MotionSimOptions so;
    so.field = o.field;
    so.seed = seed;
    so.randomize = o.randomize;
    so.params = o.params;
    so.debug = o.debug;
    MotionSim sim(so);
    MotionRequest request;
    const int warm = static_cast<int>(std::lround((so.params.transitionTime + kWarmup) / kCycleTime));
    for (int i = 0; i < warm; ++i)
      if (!sim.cycle(request)) throw Error("simulation", sim.stopReason());
    TruthTracker track;
    track.begin(sim);
    std::uniform_real_distribution<double> unit(-1, 1), hold(2, 5), u01(0, 1);
    double nextChange = sim.time(), commandStart = sim.time();
    const double end = sim.time() + o.seconds;
    const Pose2 limit = sim.clipSpeed({1e3, 0, 0});
    while (sim.time() < end && !track.falls) {
      if (sim.time() >= nextChange) {
        commandStart = sim.time();
        nextChange = sim.time() + hold(rng);
        const double kind = u01(rng);
        request.motion = MotionType::Walk;
        if (kind < 0.1) {
          request.walkSpeed = {};  // stand still a while
          request.motion = MotionType::Stand;
        } else {
          // Uniform in the box of the limits (backwards up to the backward limit), then clipped
          // to the walk's speed ellipsoid: fast, combined commands included.
          const double vx = unit(rng) > -0.4 ? u01(rng) * limit.x : -u01(rng) * 0.22;
          const double turn = unit(rng) * 1.2;  // before vy: the order of the committed figures
          request.walkSpeed = Pose2(vx, unit(rng) * 0.2, turn);
        }
      }
      if (!sim.cycle(request)) throw Error("simulation", sim.stopReason());
      track.update(sim);
      if (track.falls && o.debug && o.debug->on(kWalkFalls)) {
        const Pose2& c = request.walkSpeed;
        const Pose2& a = sim.info().walkSpeed;
        o.debug->write(kWalkFalls, {{"trial", t},
                                    {"trial_s", sim.time() - (end - o.seconds)},
                                    {"command_s", sim.time() - commandStart},
                                    {"command", {c.x, c.y, c.theta * 180 / M_PI}},
                                    {"applied", {a.x, a.y, a.theta * 180 / M_PI}}});
      }
    }
    request = MotionRequest{};
    for (int i = 0; i < static_cast<int>(2.0 / kCycleTime) && !track.falls; ++i) {
      if (!sim.cycle(request)) throw Error("simulation", sim.stopReason());
      track.update(sim);
    }
    WalkRunResult r;
    r.seconds = o.seconds;
    track.finish(sim, r);
    r.variation = sim.variation();
    result.falls += r.falls;
    ratios.push_back(r.odometryErrorRatio);
    result.trials.push_back(r);
    if (o.progress) o.progress(t + 1, o.trials);
  }
  result.odometryErrorRatioMedian = median(ratios);
  result.odometryErrorRatioMax = *std::max_element(ratios.begin(), ratios.end());
  return result;
}

WalkToResult runWalkTo(const WalkToOptions& o) {
  MotionSimOptions so;
  so.field = o.field;
  so.seed = o.seed;
  so.randomize = o.randomize;
  so.variation = o.variation;
  so.params = o.params;
  so.debug = o.debug;
  MotionSim sim(so);
  MotionRequest request;
  const int warm = static_cast<int>(std::lround((so.params.transitionTime + kWarmup) / kCycleTime));
  for (int i = 0; i < warm; ++i)
    if (!sim.cycle(request)) throw Error("simulation", sim.stopReason());
  const Eigen::Vector3d start = sim.truePose();
  const double startTime = sim.time();
  request.motion = MotionType::WalkTo;
  request.walkTarget = o.target;
  request.walkTargetId = 1;
  TruthTracker track;
  track.begin(sim);
  WalkToResult r;
  double settledSince = -1;
  while (sim.time() - startTime < o.timeLimit && !track.falls) {
    if (!sim.cycle(request)) throw Error("simulation", sim.stopReason());
    track.update(sim);
    if (sim.info().walkToReached) {
      if (settledSince < 0) settledSince = sim.time();
      if (sim.time() - settledSince > 0.5) {
        r.reached = true;
        break;
      }
    } else {
      settledSince = -1;
    }
  }
  r.time = sim.time() - startTime;
  r.target = o.target;
  const Eigen::Vector3d truth = relativeTo(start, sim.truePose());
  r.positionError = std::hypot(truth.x() - o.target.x, truth.y() - o.target.y);
  r.angleError = std::abs(Pose2::wrap(truth.z() - o.target.theta));
  const Pose2 odo = track.odometryStart.inverse() * sim.odometry().pose;
  r.odometryOffset = Eigen::Vector2d(odo.x - truth.x(), odo.y - truth.y());
  r.odometryPositionError = r.odometryOffset.norm();
  r.odometryAngleError = std::abs(Pose2::wrap(odo.theta - truth.z()));
  r.controlPositionError = std::hypot(odo.x - o.target.x, odo.y - o.target.y);
  r.controlAngleError = std::abs(Pose2::wrap(odo.theta - o.target.theta));
  r.falls = track.falls;
  r.variation = sim.variation();
  return r;
}

WalkToEvalResult evalWalkTo(int trials, std::uint64_t seed, bool randomize, const MotionEngine::Params& params,
                            const std::function<void(int, int)>& progress, const RobotVariation& variation) {
  if (trials < 1) throw Error("--trials", "must be at least 1");
  WalkToEvalResult result;
  std::vector<double> pos, ang, odo;
  for (int t = 0; t < trials; ++t) {
    const std::uint64_t s = seed * 7919ULL + static_cast<std::uint64_t>(t);
    std::mt19937_64 rng(s);
    std::uniform_real_distribution<double> angle(-M_PI, M_PI);
    const double direction = angle(rng);
    WalkToOptions o;
    o.target = Pose2(3 * std::cos(direction), 3 * std::sin(direction), angle(rng));
    o.seed = s;
    o.randomize = randomize;
    o.variation = variation;
    o.params = params;
    const WalkToResult r = runWalkTo(o);
    result.falls += r.falls;
    result.reached += r.reached;
    pos.push_back(r.positionError);
    ang.push_back(r.angleError);
    odo.push_back(r.odometryPositionError);
    result.trials.push_back(r);
    if (progress) progress(t + 1, trials);
  }
  result.positionErrorMedian = median(pos);
  result.positionErrorMax = *std::max_element(pos.begin(), pos.end());
  result.angleErrorMedian = median(ang);
  result.angleErrorMax = *std::max_element(ang.begin(), ang.end());
  result.odometryPositionErrorMedian = median(odo);
  result.odometryPositionErrorMax = *std::max_element(odo.begin(), odo.end());
  return result;
}

}  // namespace nao::sim
