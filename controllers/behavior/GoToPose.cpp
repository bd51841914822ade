#include "controllers/behavior/GoToPose.h"

#include <cmath>

namespace nao::behavior {

bool GoToPose::run(const BehaviorInput& in, const Pose2& target, MotionRequest& request) {
  if (!in.pose.valid) {
    // Lost (or not yet localized): stand and let the head find the field; lost for long, turn.
    if (lostSince_ < 0) lostSince_ = in.time;
    machine_.go(State::WaitForPose, in.time);
    haveTarget_ = false;
    reachedSince_ = -1;
    request = MotionRequest{};
    if (params_.lostTurnAfter > 0 && in.time - lostSince_ >= params_.lostTurnAfter) {
      request.motion = MotionType::Walk;
      request.walkSpeed = Pose2(0, 0, params_.lostTurnSpeed);
    }
    return false;
  }
  lostSince_ = -1;
  // The target as the estimate places it in the odometry frame.
  const Pose2 odometryTarget = in.pose.odometry * (in.pose.pose.inverse() * target);
  const Pose2 toTarget = in.pose.pose.inverse() * target;
  const double distance = std::hypot(toTarget.x, toTarget.y);
  if (haveTarget_) {
    const Pose2 moved = odometryTarget_.inverse() * odometryTarget;
    const double limit = distance < params_.nearDistance ? params_.retargetNear : params_.retargetFar;
    if (std::hypot(moved.x, moved.y) > limit || std::abs(moved.theta) > params_.retargetAngle) haveTarget_ = false;
  }
  if (!haveTarget_) {
    haveTarget_ = true;
    odometryTarget_ = odometryTarget;
    ++targetId_;
  }
  const bool arrived = distance < params_.arrivedDistance && std::abs(toTarget.theta) < params_.arrivedAngle &&
                       in.motion.walkToReached;
  if (!in.motion.walkToReached || arrived) {
    reachedSince_ = -1;
  } else if (reachedSince_ < 0) {
    reachedSince_ = in.time;
  } else if (in.time - reachedSince_ >= params_.nudgeAfter) {
    // The walk stands at its target, the estimate says not arrived: the target once more.
    odometryTarget_ = odometryTarget;
    ++targetId_;
    reachedSince_ = -1;
  }
  machine_.go(arrived ? State::Arrived : State::Walk, in.time);
  request = MotionRequest{};
  request.motion = MotionType::WalkTo;
  request.walkTarget = odometryTarget_;
  request.walkTargetInOdometry = true;
  request.walkTargetId = targetId_;
  return arrived;
}

}  // namespace nao::behavior
