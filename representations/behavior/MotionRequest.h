#pragma once
// What the behaviour asks of the body. Provided by the behaviour; until a behaviour module
// exists, a pipeline input that scenarios and tests write onto the blackboard.
#include <Eigen/Core>

#include "robot/math/Pose2.h"

namespace nao {

enum class MotionType { Stand, Walk, WalkTo, Kick, GetUp, SitDown, PlayDead };

inline const char* motionTypeName(MotionType type) {
  switch (type) {
    case MotionType::Stand: return "stand";
    case MotionType::Walk: return "walk";
    case MotionType::WalkTo: return "walk_to";
    case MotionType::Kick: return "kick";
    case MotionType::GetUp: return "get_up";
    case MotionType::SitDown: return "sit_down";
    case MotionType::PlayDead: return "play_dead";
  }
  return "?";
}

struct MotionRequest {
  MotionType motion = MotionType::Stand;
  Pose2 walkSpeed;   // Walk: vx, vy (m/s), vtheta (rad/s), robot frame; clipped to the walk's limits
  Pose2 walkTarget;  // WalkTo: a pose in the robot frame at the time the request (its id) was made
  int walkTargetId = 0;  // a new id starts a new WalkTo (the target is taken relative to the robot then)
  // WalkTo: walkTarget is a pose in the odometry frame (Odometry::pose) instead: a behaviour
  // that knows the odometry at its estimate's time sends targets free of its own latency.
  bool walkTargetInOdometry = false;
  double kickDirection = 0;  // Kick: rad, robot frame: where the ball should go
  Eigen::Vector2d ballPosition = Eigen::Vector2d(0.16, 0.05);  // Kick: the ball, robot frame (m)
  int kickId = 0;            // a new id starts a new kick
};

}  // namespace nao
