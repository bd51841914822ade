#pragma once
// What the behaviour asks of the body (MotionRequest) and what the motion engine reports back
// (MotionInfo, with the odometry). Plain representations for the robot program's blackboard.
#include <cmath>
#include <numbers>

#include <Eigen/Core>

namespace nao {

// A 2-D pose or displacement (x, y in m, theta in rad); also a walk speed (m/s, rad/s).
struct Pose2 {
  double x = 0, y = 0, theta = 0;

  Pose2() = default;
  Pose2(double x_, double y_, double theta_) : x(x_), y(y_), theta(theta_) {}

  // This pose followed by `o` expressed in this pose's frame.
  Pose2 operator*(const Pose2& o) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * o.x - s * o.y, y + s * o.x + c * o.y, wrap(theta + o.theta)};
  }
  Eigen::Vector2d operator*(const Eigen::Vector2d& p) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * p.x() - s * p.y(), y + s * p.x() + c * p.y()};
  }
  Pose2 inverse() const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {-(c * x + s * y), s * x - c * y, -theta};
  }
  Eigen::Vector2d translation() const { return {x, y}; }
  static double wrap(double a) {
    a = std::remainder(a, 2 * std::numbers::pi);
    return a <= -std::numbers::pi ? a + 2 * std::numbers::pi : a;
  }
};

enum class MotionType { Stand, Walk, WalkTo, Kick, GetUp, SitDown, PlayDead };
const char* motionTypeName(MotionType type);

struct MotionRequest {
  MotionType motion = MotionType::Stand;
  Pose2 walkSpeed;   // Walk: vx, vy (m/s), vtheta (rad/s), robot frame; clipped to the walk's limits
  Pose2 walkTarget;  // WalkTo: a pose in the robot frame at the time the request (its id) was made
  int walkTargetId = 0;  // a new id starts a new WalkTo (the target is taken relative to the robot then)
  double kickDirection = 0;  // Kick: rad, robot frame: where the ball should go
  Eigen::Vector2d ballPosition = Eigen::Vector2d(0.16, 0.05);  // Kick: the ball, robot frame (m)
  int kickId = 0;            // a new id starts a new kick
};

struct MotionInfo {
  MotionType motion = MotionType::Stand;  // the motion now executed
  bool stable = true;          // standing or walking on its feet, nothing in transition
  bool walkToReached = false;  // WalkTo: the target is reached and the robot stands
  bool kickDone = false;       // Kick: the kick with the current kickId is over
  bool upright = true;         // not fallen (after a get-up: true again)
  int getUpAttempts = 0;
  Pose2 walkSpeed;             // the speed the walk applies now (after its limits and ramps)
};

// Where the robot went: its pose in the odometry frame (fixed to the ground where the robot
// program started), from the legs' kinematics and the gyro.
struct Odometry {
  Pose2 pose;
};

}  // namespace nao
