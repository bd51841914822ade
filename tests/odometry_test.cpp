// The walk's odometry beyond the legs' kinematics: the inertial check of the feet's velocities
// (InertialOdometry, on synthetic gaits with known truth), a twisting sole turning the robot
// about its ground contact, the simulated IMU's velocity change against the simulator's truth,
// and the odometry of randomised robots walking to 3 m targets against the truth.
// NAO_TEST_QUICK (set for the sanitizer run) shortens the simulations.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "controllers/InertialOdometry.h"
#include "controllers/Kinematics.h"
#include "controllers/Walk.h"
#include "robot/ForwardKinematics.h"
#include "robot/RobotDimensions.h"
#include "scenarios/WalkEval.h"
#include "sim/World.h"

namespace nao {
namespace {

constexpr double kCycle = 0.012;
constexpr double kDeg = M_PI / 180;

bool quick() { return std::getenv("NAO_TEST_QUICK") != nullptr; }

// A gait-like velocity (m/s): forward with the stride's surge, sideways with its sway.
Eigen::Vector2d gaitVelocity(double t) {
  return {0.3 + 0.08 * std::sin(2 * M_PI * 2 * t), 0.06 * std::sin(2 * M_PI * t)};
}

struct SyntheticRun {
  double filteredError = 0;    // m, the filter's integrated position against the truth
  double kinematicError = 0;   // m, the followed foot's integrated velocity against the truth
  Eigen::Vector2d bias = Eigen::Vector2d::Zero();
  int rejected = 0;
};

// 10 s of the gait, turning at `turnRate`. The IMU measures each cycle's velocity change with a
// constant bias in the robot frame (a tilt that is off) and white noise; the followed foot's
// kinematics measure the velocity with noise, and in `slips` cycles it moves under the robot
// by `slip` (m/s) -- a late landing.
SyntheticRun runSynthetic(const Eigen::Vector2d& accelerometerBias, const Eigen::Vector2d& slip, int slipEvery,
                          double turnRate = 0) {
  std::mt19937 rng(7);
  std::normal_distribution<double> kinematicNoise(0, 0.01), imuNoise(0, 0.002);
  const auto noise = [&rng](std::normal_distribution<double>& n) {
    const double x = n(rng);  // drawn in a fixed order (a function's arguments are not)
    const double y = n(rng);
    return Eigen::Vector2d(x, y);
  };
  InertialOdometry filter;
  SyntheticRun run;
  Eigen::Vector2d truth = Eigen::Vector2d::Zero(), filtered = Eigen::Vector2d::Zero(), kinematic = Eigen::Vector2d::Zero();
  Eigen::Vector2d last = gaitVelocity(0);
  const double turn = turnRate * kCycle;
  double heading = 0;
  for (int k = 0; k < 833; ++k) {
    const double t = k * kCycle;
    const Eigen::Vector2d v = gaitVelocity(t);  // robot frame at the cycle's start
    // The last cycle's velocity in this cycle's frame, plus the change.
    const Eigen::Vector2d imuNow = noise(imuNoise);
    const Eigen::Vector2d imuDelta =
        k == 0 ? Eigen::Vector2d(Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN()))
               : Eigen::Vector2d(v - Eigen::Rotation2Dd(-turn) * last + accelerometerBias * kCycle + imuNow);
    Eigen::Vector2d foot = v + noise(kinematicNoise);
    if (slipEvery > 0 && k % slipEvery < 3 && k > 10) foot += slip;
    const Eigen::Vector2d estimate = filter.update(kCycle, turn, imuDelta, foot, 1.0, Eigen::Vector2d::Zero(), 0.0);
    const Eigen::Rotation2Dd toWorld(heading);
    truth += toWorld * v * kCycle;
    filtered += toWorld * estimate * kCycle;
    kinematic += toWorld * foot * kCycle;
    heading += turn;
    last = v;
  }
  run.filteredError = (filtered - truth).norm();
  run.kinematicError = (kinematic - truth).norm();
  run.bias = filter.bias();
  run.rejected = filter.rejected();
  return run;
}

TEST(InertialOdometry, FollowsFeetThatAgreeWithTheImuAndLearnsItsBias) {
  // An IMU tilted by about 1 deg: 0.17 m/s^2 of gravity in its horizontal reading.
  const Eigen::Vector2d bias(0.17, -0.1);
  const SyntheticRun r = runSynthetic(bias, Eigen::Vector2d::Zero(), 0);
  std::printf("no slip: filtered %.2f mm, kinematic %.2f mm off after 3 m; bias %.3f %.3f m/s^2; %d rejected\n",
              1000 * r.filteredError, 1000 * r.kinematicError, r.bias.x(), r.bias.y(), r.rejected);
  // The kinematics' own noise walks 3-6 mm in 3 m; the filter adds no more than 3 mm to it.
  EXPECT_LT(r.filteredError, r.kinematicError + 0.003);
  EXPECT_LT(r.filteredError, 0.01);
  EXPECT_NEAR(r.bias.x(), bias.x(), 0.03);
  EXPECT_NEAR(r.bias.y(), bias.y(), 0.03);
  EXPECT_LT(r.rejected, 20);  // a clean foot is (nearly) never rejected
}

// The same turning at 1 rad/s (walking in a circle): the velocity turns with the robot, the
// accelerometer's bias does not (it is the body's).
TEST(InertialOdometry, KeepsTheBiasInTheBodyWhileTurning) {
  const Eigen::Vector2d bias(0.17, -0.1);
  const SyntheticRun r = runSynthetic(bias, Eigen::Vector2d::Zero(), 0, 1.0);
  std::printf("turning: filtered %.2f mm, kinematic %.2f mm off; bias %.3f %.3f m/s^2; %d rejected\n", 1000 * r.filteredError,
              1000 * r.kinematicError, r.bias.x(), r.bias.y(), r.rejected);
  EXPECT_LT(r.filteredError, r.kinematicError + 0.003);
  EXPECT_LT(r.filteredError, 0.01);
  EXPECT_NEAR(r.bias.x(), bias.x(), 0.03);
  EXPECT_NEAR(r.bias.y(), bias.y(), 0.03);
}

TEST(InertialOdometry, IgnoresAFootThatMovesUnderTheRobot) {
  // Three cycles a step (every 21 cycles) the foot slides 6 mm a cycle forward and 4 mm sideways.
  const SyntheticRun r = runSynthetic(Eigen::Vector2d(0.1, 0.05), Eigen::Vector2d(0.5, 0.33), 21);
  std::printf("slipping foot: filtered %.2f mm, kinematic %.2f mm off after 3 m; %d rejected\n", 1000 * r.filteredError,
              1000 * r.kinematicError, r.rejected);
  EXPECT_GT(r.kinematicError, 0.5);  // the kinematics alone: 39 slips of 3 cycles, 7 mm each
  EXPECT_LT(r.filteredError, 0.01);
  EXPECT_GE(r.rejected, 3 * 38);
}

TEST(InertialOdometry, TakesTheKinematicsBackWhenItLosesTrack) {
  // The robot put down moving (a push the IMU did not see): the feet agree on 0.2 m/s, the IMU
  // says no change. The filter rejects them at first, then takes them.
  InertialOdometry filter;
  filter.update(kCycle, 0, Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN()), Eigen::Vector2d::Zero(), 1,
                Eigen::Vector2d::Zero(), 1);
  Eigen::Vector2d v = Eigen::Vector2d::Zero();
  for (int k = 0; k < 40; ++k)
    v = filter.update(kCycle, 0, Eigen::Vector2d::Zero(), Eigen::Vector2d(0.2, 0), 1, Eigen::Vector2d(0.2, 0), 1);
  EXPECT_NEAR(v.x(), 0.2, 0.01);
  EXPECT_NEAR(v.y(), 0.0, 0.01);
}

TEST(InertialOdometry, BadNumbersGiveNoNaN) {
  InertialOdometry filter;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Eigen::Vector2d bad = Eigen::Vector2d::Constant(nan);
  Eigen::Vector2d v = filter.update(kCycle, 0, bad, bad, 1, Eigen::Vector2d(0.1, 0), nan);
  EXPECT_TRUE(v.allFinite());
  for (int k = 0; k < 10; ++k) {
    v = filter.update(kCycle, nan, bad, Eigen::Vector2d(0.1, 0), 1, bad, 1);
    EXPECT_TRUE(v.allFinite());
    v = filter.update(0, 0, Eigen::Vector2d::Zero(), Eigen::Vector2d(0.1, 0), 1, Eigen::Vector2d(0.1, 0), 1);
    EXPECT_TRUE(v.allFinite());
  }
  EXPECT_NEAR(v.x(), 0.1, 1e-9);
  // A NaN turn with a finite IMU reading (one bad IMU angle upstream) does not stick either.
  v = filter.update(kCycle, nan, Eigen::Vector2d::Zero(), Eigen::Vector2d(0.1, 0), 1, Eigen::Vector2d(0.1, 0), 1);
  EXPECT_TRUE(v.allFinite());
  for (int k = 0; k < 5; ++k) v = filter.update(kCycle, 0, Eigen::Vector2d::Zero(), Eigen::Vector2d(0.1, 0), 1, Eigen::Vector2d(0.1, 0), 1);
  EXPECT_TRUE(v.allFinite());
  EXPECT_TRUE(filter.bias().allFinite());
  EXPECT_NEAR(v.x(), 0.1, 1e-6);
}

// The loaded left sole twists on the floor with the whole robot: the joints do not move, the
// gyro reports the turn. The sole's ground contact stays put, so the robot frame's origin moves
// on an arc about it; turning the robot about its own origin (the old odometry) misses that.
TEST(Walk, OdometryTurnsATwistingSoleAboutItsContact) {
  for (bool twist : {true, false}) {
    Walk::Params params;
    params.twistAboutContact = twist;
    Walk walk(params);
    SensorFrame frame;
    frame.joints.position = walk.standPosture();
    for (int i = 0; i < 4; ++i) frame.fsr.weight[i] = 1.3;  // all on the left foot, evenly
    const double rate = 0.6;                                // rad/s
    frame.inertial.accelerometer = Eigen::Vector3d(0, 0, 9.81);
    // The contact: the centre of the left foot's FSRs, in the robot frame.
    const Eigen::Isometry3d sole = torsoToSole(frame.joints.position, BodySide::Left);
    const Eigen::Vector3d fsrCentre((dims::fsrX(LFsrFL) + dims::fsrX(LFsrRL)) / 2, (dims::fsrY(LFsrFL) + dims::fsrY(LFsrFR)) / 2, 0);
    const Eigen::Vector2d contact = (sole * fsrCentre).head<2>();
    // 1.2 s standing still (the accelerometer's check settles), then 30 cycles of twisting. The
    // accelerometer reads the arc's small centripetal acceleration, w^2 r (0.02 m/s^2).
    const int still = 100, cycles = 30;
    for (int k = 0; k <= still + cycles; ++k) {
      const bool twisting = k > still;
      frame.inertial.gyroscope = Eigen::Vector3d(0, 0, twisting ? rate : 0.0);
      if (twisting) {
        // The origin's position relative to the contact, in the robot frame: -contact, turning.
        const Eigen::Vector2d centripetal = rate * rate * contact;  // towards the contact
        frame.inertial.accelerometer = Eigen::Vector3d(centripetal.x(), centripetal.y(), 9.81);
      }
      frame.time = k * kCycle;
      walk.updateOdometry(frame);
      if (k == still) walk.resetOdometry();
    }
    const double turned = rate * cycles * kCycle;
    const Eigen::Vector2d truth = contact + Eigen::Rotation2Dd(turned) * (-contact);
    const Pose2& odo = walk.odometry();
    const double error = std::hypot(odo.x - truth.x(), odo.y - truth.y());
    std::printf("twist %.1f deg about the contact (%.1f, %.1f) cm, twist %s: odometry (%.2f, %.2f) mm, truth (%.2f, %.2f) mm\n",
                turned / kDeg, 100 * contact.x(), 100 * contact.y(), twist ? "on" : "off", 1000 * odo.x, 1000 * odo.y,
                1000 * truth.x(), 1000 * truth.y());
    EXPECT_NEAR(odo.theta, turned, 1e-6);
    if (twist)
      EXPECT_LT(error, 1e-3);  // the filter takes a few cycles to follow the twist's sudden start
    else
      EXPECT_GT(error, 5e-3);  // what the old odometry missed
  }
}

// The walk's odometry with the inertial check, on frames with a known truth: the robot moves
// off to 0.25 m/s over its loaded left foot (the legs' kinematics and the accelerometer agree);
// in one cycle the foot slides 8 mm back under the robot (a late landing), which
// the kinematics take for 8 mm of forward motion. With an accelerometer reading +g upwards the
// odometry rejects that cycle; reading -g (a sign convention other than ours, or a broken
// sensor) the check is off and the odometry is the kinematics'.
TEST(Walk, OdometryRejectsASlidingFootOnlyWithAPlausibleImu) {
  for (double gravity : {9.81, -9.81}) {
    Walk walk;
    SensorFrame frame;
    const JointArray stand = walk.standPosture();
    JointArray joints = stand;
    const Eigen::Isometry3d left0 = torsoToSole(stand, BodySide::Left), right0 = torsoToSole(stand, BodySide::Right);
    for (int i = 0; i < 4; ++i) frame.fsr.weight[i] = 1.3;
    const double speed = 0.25, slide = 0.008;
    const int start = 100, ramp = 20, cycles = 140, slideAt = 130;  // 1.2 s standing (the IMU's check settles)
    const double acceleration = speed / (ramp * kCycle);
    double footBack = 0, truth = 0;  // how far the foot is behind its start (torso frame); the robot's travel
    for (int k = 0; k <= cycles; ++k) {
      // Constant acceleration within a cycle: the accelerometer reads it, the cycle's mean velocity follows.
      const bool accelerating = k > start && k <= start + ramp;
      const double meanVelocity = k <= start ? 0.0 : accelerating ? acceleration * kCycle * (k - start - 0.5) : speed;
      frame.inertial.accelerometer = Eigen::Vector3d(accelerating ? acceleration : 0.0, 0, gravity);
      footBack += meanVelocity * kCycle;
      truth += meanVelocity * kCycle;
      if (k == slideAt) footBack += slide;
      Eigen::Isometry3d left = left0;
      left.translation().x() -= footBack;
      ASSERT_TRUE(legsIK(left, right0, joints));
      frame.joints.position = joints;
      frame.time = k * kCycle;
      walk.updateOdometry(frame);
    }
    const double odo = walk.odometry().x;
    std::printf("accelerometer %+.2f m/s^2 up: odometry %.1f mm, truth %.1f mm (the slide: %.1f mm)\n", gravity, 1000 * odo, 1000 * truth,
                1000 * slide);
    if (gravity > 0)
      EXPECT_NEAR(odo, truth, 0.0015);
    else
      EXPECT_NEAR(odo, truth + slide, 0.0015);
  }
}

// The simulated IMU against the simulator's truth: one cycle's velocity change of the robot
// frame's origin (the torso), walking and turning, as ImuVelocityChange computes it from the
// accelerometer, gyro and tilt, predicts the truth's to a small fraction of a millimetre per
// cycle. That is the premise of the inertial check (a loaded foot's kinematics scatter by
// 0.2-4 mm a cycle).
TEST(Odometry, TheImuPredictsTheTorsosVelocityChange) {
  sim::MotionSimOptions o;
  sim::MotionSim sim(o);
  MotionRequest request;
  for (int i = 0; i < 150; ++i) ASSERT_TRUE(sim.cycle(request));
  request.motion = MotionType::Walk;
  request.walkSpeed = Pose2(0.3, 0.05, 0.4);
  ImuVelocityChange imu;
  const Eigen::Vector3d imuPosition(dims::kImuX, dims::kImuY, dims::kImuZ);
  Eigen::Isometry3d lastTorso = sim.world().torsoPose(0);
  double lastYaw = sim.truePose().z();
  Eigen::Vector2d lastVelocity = Eigen::Vector2d::Zero();
  double lastTurn = 0;
  bool haveVelocity = false;
  std::vector<double> residuals;
  const int cycles = quick() ? 250 : 500;
  for (int i = 0; i < cycles; ++i) {
    ASSERT_TRUE(sim.cycle(request));
    const Eigen::Isometry3d torso = sim.world().torsoPose(0);
    const double yaw = sim.truePose().z();
    const double turn = Pose2::wrap(yaw - lastYaw);
    // The truth: the cycle's mean velocity of the torso origin, in the robot frame at its start.
    const Eigen::Vector2d moved = (torso.translation() - lastTorso.translation()).head<2>();
    const Eigen::Vector2d velocity = Eigen::Rotation2Dd(-lastYaw) * moved / kCycle;
    const SensorFrame& f = sim.frame();
    const Eigen::Vector2d change =
        imu.update(torsoTilt(f.inertial.angle.x(), f.inertial.angle.y()), f.inertial.accelerometer, f.inertial.gyroscope, turn, kCycle, imuPosition);
    // The last cycle's velocity carried into this cycle's start frame, plus the IMU's change.
    if (haveVelocity && i > 80)  // past the walk's start
      residuals.push_back((velocity - (Eigen::Rotation2Dd(-lastTurn) * lastVelocity + change)).norm() * kCycle);
    lastVelocity = velocity;
    lastTurn = turn;
    haveVelocity = true;
    lastTorso = torso;
    lastYaw = yaw;
  }
  std::sort(residuals.begin(), residuals.end());
  const double median = residuals[residuals.size() / 2], p99 = residuals[residuals.size() * 99 / 100];
  std::printf("IMU prediction of the next cycle's displacement: median %.3f mm, 99 %% %.3f mm, max %.3f mm (%zu cycles)\n",
              1000 * median, 1000 * p99, 1000 * residuals.back(), residuals.size());
  EXPECT_LT(median, 0.05e-3);
  EXPECT_LT(p99, 0.3e-3);
}

// Randomised robots (masses +-5 %, joint offsets +-1 deg, floor friction 0.6-1.0) walking to
// 3 m targets: the odometry against the truth at the end. Seed 5's trials 0-7 include one whose
// odometry (kinematics alone) ended 5.7 cm off: a late landing's foot followed in the air, and
// the soles' twists turned about the wrong point; with the inertial check and the twist 2.2 cm.
TEST(Odometry, HoldsOnRandomisedRobotsWalkingTo3mTargets) {
  const sim::WalkToEvalResult r = sim::evalWalkTo(quick() ? 2 : 8, 5, true, MotionEngine::Params{});
  std::vector<double> errors;
  for (const auto& t : r.trials) {
    std::printf("randomised walk to (%.2f, %.2f) m: odometry off by %.1f mm, robot %.1f mm from the target, friction %.2f\n",
                t.target.x, t.target.y, 1000 * t.odometryPositionError, 1000 * t.positionError, t.variation.friction);
    errors.push_back(t.odometryPositionError);
  }
  std::sort(errors.begin(), errors.end());
  EXPECT_EQ(r.falls, 0);
  EXPECT_LT(errors.back(), 0.035);
  EXPECT_LT(errors[(errors.size() - 1) / 2], 0.02);
}

}  // namespace
}  // namespace nao
