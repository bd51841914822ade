#pragma once
// Motion in the simulator, measured against ground truth: one NAO running the robot program's
// motion engine (no cameras), optionally a "foreign" robot (link masses, joint offsets, floor
// friction randomised), driven by motion requests. Used by `walk`, `kick` and `eval walk`, and
// by the motion tests.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "controllers/FallDetector.h"
#include "controllers/HeadControl.h"
#include "controllers/MotionEngine.h"
#include "controllers/RobotProgram.h"
#include "perception/FieldDimensions.h"
#include "representations/behavior/MotionRequest.h"
#include "representations/motion/MotionInfo.h"
#include "representations/motion/Odometry.h"

namespace nao::sim {

class World;
class SimBackend;

// The spread of the randomised robot ("foreign robots").
struct RobotVariation {
  double massSpread = 0.05;          // each link's mass x U(1 - s, 1 + s)
  double jointOffset = M_PI / 180;   // each joint's calibration offset U(-a, a), rad
  double frictionMin = 0.6, frictionMax = 1.0;  // floor friction
};

struct AppliedVariation {
  bool randomized = false;
  double totalMass = 0;  // kg
  double friction = 1.0;
  double maxJointOffset = 0;  // rad
  JointArray jointOffsets{};  // rad, true angle = reading + offset
};

// A practice hall for motion trials: an SPL-style field of 24 m x 16 m, so that 30 s of walking
// in a straight line, a wandering random walk or a long kick meets no goal.
FieldDimensions motionField();

struct MotionSimOptions {
  FieldDimensions field = motionField();
  std::uint64_t seed = 1;
  bool randomize = false;
  RobotVariation variation;
  Eigen::Vector3d pose = Eigen::Vector3d::Zero();  // start pose in the field (x, y, theta)
  std::vector<Eigen::Vector3d> balls;
  MotionEngine::Params params;
  // Initial joint angles; empty = the walk's stand posture (the robot starts standing).
  std::vector<double> posture;
  DebugChannels* debug = nullptr;  // the robot program's debug channels (not owned); null: none
};

// One robot in a world running the robot program (no cameras), one 12 ms cycle per call, the
// motion and head requests written where the behaviour would write them.
class MotionSim {
 public:
  explicit MotionSim(const MotionSimOptions& options);
  ~MotionSim();

  // One cycle with this request (and head request). False when the simulation failed.
  bool cycle(const MotionRequest& request, const HeadMotionRequest& head = {});

  World& world() { return *world_; }
  RobotProgram& program() { return *program_; }
  const SensorFrame& frame() const;
  const FallState& fallState() const;
  const MotionInfo& info() const;
  const Odometry& odometry() const;
  // The walk's speed limits (what the motion engine clips a request to).
  Pose2 clipSpeed(const Pose2& speed) const { return walkLimits_.clipSpeed(speed); }
  const AppliedVariation& variation() const { return variation_; }
  double time() const;
  // Ground truth: the robot's pose (x, y, theta) and whether it lies (torso tilt > 50 deg).
  Eigen::Vector3d truePose() const;
  double trueTilt() const;  // rad
  bool trueFallen() const { return trueTilt() > 50 * M_PI / 180; }
  std::string stopReason() const;

 private:
  std::unique_ptr<World> world_;
  std::unique_ptr<SimBackend> backend_;
  std::unique_ptr<RobotProgram> program_;
  Walk walkLimits_;
  AppliedVariation variation_;
};

// Draws a variation and applies it to robot `robot` of the world.
AppliedVariation applyVariation(World& world, int robot, const RobotVariation& v, std::uint64_t seed);

// A walk with a fixed speed: 1 s standing, `seconds` walking, then stopping.
struct WalkRunOptions {
  FieldDimensions field = motionField();
  Pose2 speed;              // vx, vy (m/s), vtheta (rad/s)
  double seconds = 10;
  std::uint64_t seed = 1;
  bool randomize = false;
  RobotVariation variation;
  MotionEngine::Params params;
  DebugChannels* debug = nullptr;  // not owned; null: none
};

struct WalkRunResult {
  double seconds = 0;             // walking time measured
  double distance = 0;            // m, ground-truth path length (sampled every 0.5 s)
  Eigen::Vector2d displacement = Eigen::Vector2d::Zero();  // m, start robot frame
  double turned = 0;              // rad, unwrapped
  double meanSpeed = 0;           // m/s: |displacement| / seconds
  double forwardSpeed = 0, sidewaysSpeed = 0, turnRate = 0;  // along the start frame's axes, rad/s
  int falls = 0;
  double odometryError = 0;       // m: |odometry - truth| at the end (start frame)
  double odometryErrorRatio = 0;  // odometryError / distance
  double odometryAngleError = 0;  // rad
  double maxTilt = 0;             // rad
  AppliedVariation variation;
};

WalkRunResult runWalk(const WalkRunOptions& options);

// `eval walk`: trials of `seconds` each with the walk command changing every 2-5 s at random.
struct WalkEvalOptions {
  FieldDimensions field = motionField();
  int trials = 20;
  double seconds = 60;
  std::uint64_t seed = 1;
  bool randomize = false;
  RobotVariation variation;
  MotionEngine::Params params;
  DebugChannels* debug = nullptr;  // not owned; null: none
  std::function<void(int done, int total)> progress;
};

struct WalkEvalResult {
  std::vector<WalkRunResult> trials;
  int falls = 0;
  double odometryErrorRatioMedian = 0, odometryErrorRatioMax = 0;
};

WalkEvalResult evalWalk(const WalkEvalOptions& options);

// Walk to a robot-relative target on odometry alone; the error is measured by ground truth
// once the robot stands (or at the time limit).
struct WalkToOptions {
  FieldDimensions field = motionField();
  Pose2 target{3, 0, 0};
  double timeLimit = 40;
  std::uint64_t seed = 1;
  bool randomize = false;
  RobotVariation variation;
  MotionEngine::Params params;
  DebugChannels* debug = nullptr;  // not owned; null: none
};

struct WalkToResult {
  Pose2 target;               // relative to the start
  bool reached = false;       // the engine reported the target reached before the time limit
  double time = 0;            // s until then
  double positionError = 0;   // m, ground truth
  double angleError = 0;      // rad, ground truth
  // Where the error comes from: the odometry's final pose against ground truth (both relative
  // to the start), and the target against the odometry (what the controller left).
  double odometryPositionError = 0, odometryAngleError = 0;  // m, rad: odometry - truth
  Eigen::Vector2d odometryOffset = Eigen::Vector2d::Zero();  // m, odometry - truth (start frame)
  double controlPositionError = 0, controlAngleError = 0;    // m, rad: odometry - target
  int falls = 0;
  AppliedVariation variation;
};

WalkToResult runWalkTo(const WalkToOptions& options);

// Random targets 3 m away (random direction and final heading).
struct WalkToEvalResult {
  std::vector<WalkToResult> trials;
  int falls = 0, reached = 0;
  double positionErrorMedian = 0, positionErrorMax = 0, angleErrorMedian = 0, angleErrorMax = 0;
  double odometryPositionErrorMedian = 0, odometryPositionErrorMax = 0;
};

WalkToEvalResult evalWalkTo(int trials, std::uint64_t seed, bool randomize, const MotionEngine::Params& params,
                            const std::function<void(int, int)>& progress = {}, const RobotVariation& variation = {});

}  // namespace nao::sim
