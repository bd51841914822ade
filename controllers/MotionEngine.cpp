#include "controllers/MotionEngine.h"

#include <algorithm>
#include <cmath>

#include "controllers/Kinematics.h"
#include "robot/RobotDimensions.h"

namespace nao {

NAO_DEBUG_CHANNEL(kWalkToTrace, "walk_to_trace",
                  "walking to a target, every 8th cycle: the target relative to the robot (m, deg), the "
                  "commanded speed (m/s, deg/s) and the walk's phase");
const char* const kPhaseNames[] = {"standing", "starting", "walking", "stopping"};  // Walk::Phase

namespace {

constexpr double kCycle = 0.012;

double smoothstep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

// Crouching: torso low above the feet, arms down, as a NAO sits before its stiffness goes off.
JointArray sitPosture(const JointArray& arms) {
  JointArray j = arms;
  Eigen::Isometry3d l = Eigen::Isometry3d::Identity(), r = Eigen::Isometry3d::Identity();
  l.translation() = Eigen::Vector3d(-0.01, dims::kHipY, -0.135);
  r.translation() = Eigen::Vector3d(-0.01, -dims::kHipY, -0.135);
  legsIK(l, r, j);
  j[HeadYaw] = 0;
  j[HeadPitch] = 0;
  return j;
}

// While falling: knees bent, arms forward (falling forwards) or along the body (backwards),
// head turned away from the impact.
JointArray safeFallPosture(const JointArray& now, FallDirection direction) {
  JointArray j = now;
  const bool front = direction == FallDirection::Front;
  j[HeadYaw] = 0;
  j[HeadPitch] = front ? -0.5 : 0.4;
  j[LShoulderPitch] = j[RShoulderPitch] = front ? 0.1 : 1.6;
  j[LShoulderRoll] = 0.3;
  j[RShoulderRoll] = -0.3;
  j[LElbowYaw] = -1.5;
  j[RElbowYaw] = 1.5;
  j[LElbowRoll] = front ? -0.6 : -0.1;
  j[RElbowRoll] = front ? 0.6 : 0.1;
  j[LHipPitch] = j[RHipPitch] = -0.6;
  j[LKneePitch] = j[RKneePitch] = 1.2;
  j[LAnklePitch] = j[RAnklePitch] = -0.6;
  j[LHipRoll] = j[RHipRoll] = 0;
  j[LAnkleRoll] = j[RAnkleRoll] = 0;
  j[LHipYawPitch] = 0;
  return j;
}

}  // namespace

MotionEngine::MotionEngine(const Params& params)
    : params_(params), walk_(params.walk), kick_(params.kick), getUp_(params.getUp) {}

// The robot pose (robot frame) from which a straight kick with the chosen foot sends the ball
// in `direction`: heading = direction, the ball at Kick::ballTarget in front of the foot.
Pose2 MotionEngine::kickPose(const Eigen::Vector2d& ball, double direction, bool leftFoot) const {
  const Eigen::Vector2d target = Kick::ballTarget(leftFoot, params_.kick);
  const double c = std::cos(direction), s = std::sin(direction);
  return {ball.x() - (c * target.x() - s * target.y()), ball.y() - (s * target.x() + c * target.y()), direction};
}

bool MotionEngine::wantsFeet(const MotionRequest& r) const {
  return r.motion == MotionType::Stand || r.motion == MotionType::Walk || r.motion == MotionType::WalkTo ||
         r.motion == MotionType::Kick || r.motion == MotionType::GetUp;
}

void MotionEngine::enter(State state, const SensorFrame& frame) {
  state_ = state;
  stateStart_ = frame.time;
  from_ = frame.joints.position;
}

JointRequest MotionEngine::interpolate(const SensorFrame& frame, const JointArray& goal, double duration, double stiffness) {
  JointRequest out;
  const double s = duration > 0 ? smoothstep((frame.time - stateStart_) / duration) : 1.0;
  for (int j = 0; j < NumJoints; ++j) out.position[j] = from_[j] + s * (goal[j] - from_[j]);
  out.stiffness.fill(stiffness);
  return out;
}

void MotionEngine::applyHead(JointRequest& out, const HeadJointRequest& head) const {
  out.position[HeadYaw] = clampToLimits(HeadYaw, head.yaw);
  out.position[HeadPitch] = clampToLimits(HeadPitch, head.pitch);
  out.stiffness[HeadYaw] = out.stiffness[HeadPitch] = head.stiffness;
}

std::array<double, 4> MotionEngine::raisedArm(ArmMotionRequest::Arm side) {
  const double m = side == ArmMotionRequest::Arm::Left ? 1.0 : -1.0;  // the left arm mirrors the right one
  return {-1.45, m * 0.15, -m * 1.57, -m * 0.05};
}

// The raised arm over the motion's own arm angles, blended in and out over armRaiseTime. Only
// while the walk stands: a raised arm moves the centre of mass about a centimetre, which the
// stand holds and the walk's balance does not plan for; walking (or any other motion) lowers it.
// The other arm is asked for only once the first is down.
void MotionEngine::applyArm(JointRequest& out, const SensorFrame& frame, const ArmMotionRequest& arm) {
  const double dt = armLastTime_ < 0 ? 0.0 : std::clamp(frame.time - armLastTime_, 0.0, 0.1);
  armLastTime_ = frame.time;
  if (state_ != State::Walk) {  // the kick, the get-up, a fall, sitting: the motion owns the arms
    armBlend_ = 0;
    info_.armRaised = false;
    return;
  }
  if (armBlend_ == 0 && arm.raise != ArmMotionRequest::Arm::None) armSide_ = arm.raise;
  const bool up = walk_.standing() && arm.raise == armSide_;
  const double step = params_.armRaiseTime > 0 ? dt / params_.armRaiseTime : 1.0;
  armBlend_ = std::clamp(armBlend_ + (up ? step : -step), 0.0, 1.0);
  const int first = armSide_ == ArmMotionRequest::Arm::Left ? LShoulderPitch : RShoulderPitch;
  const std::array<double, 4> raised = raisedArm(armSide_);
  const double s = smoothstep(armBlend_);
  bool reached = armBlend_ == 1.0;
  for (int k = 0; k < 4; ++k) {
    const int j = first + k;
    out.position[j] += s * (raised[k] - out.position[j]);
    reached = reached && std::abs(frame.joints.position[j] - raised[k]) < 0.1;
  }
  info_.armRaised = reached;
}

// WalkTo: the remaining offset to the target in the odometry frame, turned into a walk speed.
// Far away the robot faces its path (forward is the fastest) and slows down in time to stop
// (v <= sqrt(2 a d)); near, it turns to the target's heading and steps there
// omnidirectionally and slowly, so that the last steps are small and it stops on the spot.
Pose2 MotionEngine::walkToSpeed(const Pose2& target, double positionTolerance, double angleTolerance, bool byStopPose) {
  walkTarget_ = target;
  // The remaining offset from where the robot would stand if it stopped now (the body's sway
  // within a step would otherwise decide when the target counts as reached). WalkTo counts the
  // step in the air too: it lands where the walk sends it, the other foot closes beside it.
  // Steering by the feet as they are overshot by that step and dithered near the target (2 s
  // longer walks, each small step adding odometry error). The kick's approach keeps the feet as
  // they are: its ball placement was measured with that (median travel 3.28 m against 2.94 m).
  const Pose2& from = byStopPose ? walk_.stopPoseEstimate() : walk_.standPoseEstimate();
  const Pose2 rel = from.inverse() * walkTarget_;
  const double distance = std::hypot(rel.x, rel.y);
  const Params& p = params_;
  if (distance < positionTolerance && std::abs(rel.theta) < angleTolerance) walkToStopped_ = true;
  if (walkToStopped_ && distance < p.walkToResumePosition * positionTolerance &&
      std::abs(rel.theta) < p.walkToResumeAngle * angleTolerance)
    return {};
  walkToStopped_ = false;
  // Far: face the path. Near: the target's heading. In between a blend.
  const double pathAngle = std::atan2(rel.y, rel.x);
  const double far = std::clamp((distance - p.walkToNearDistance) / p.walkToNearDistance, 0.0, 1.0);
  Pose2 farSpeed, nearSpeed;
  farSpeed.theta = std::clamp(p.walkToTurnGain * pathAngle, -p.walkToMaxTurn, p.walkToMaxTurn);
  const double facing = std::max(0.0, std::cos(pathAngle));
  const double brake = std::sqrt(2 * p.walkToDeceleration * std::max(0.0, distance - 0.5 * p.walkToNearDistance));
  farSpeed.x = std::min(walk_.params().maxForward, brake) * facing * facing;
  farSpeed.y = std::clamp(p.walkToGain * rel.y, -0.05, 0.05);
  nearSpeed.theta = std::clamp(p.walkToTurnGain * rel.theta, -p.walkToMaxTurn, p.walkToMaxTurn);
  nearSpeed.x = std::clamp(p.walkToGain * rel.x, -p.walkToNearSpeed, p.walkToNearSpeed);
  nearSpeed.y = std::clamp(p.walkToGain * rel.y, -p.walkToNearSpeed, p.walkToNearSpeed);
  const Pose2 speed(far * farSpeed.x + (1 - far) * nearSpeed.x, far * farSpeed.y + (1 - far) * nearSpeed.y,
                    far * farSpeed.theta + (1 - far) * nearSpeed.theta);
  return walk_.clipSpeed(speed);
}

void MotionEngine::traceWalkTo(const SensorFrame& frame, const Pose2& speed, const char* what) const {
  if (!debug_->on(kWalkToTrace) || static_cast<int>(frame.time / kCycle) % 8 != 0) return;
  const Pose2 rel = odometry_.pose.inverse() * walkTarget_;
  debug_->write(kWalkToTrace, {{"for", what},
                               {"target", {rel.x, rel.y, rel.theta * 180 / M_PI}},
                               {"speed", {speed.x, speed.y, speed.theta * 180 / M_PI}},
                               {"phase", kPhaseNames[static_cast<int>(walk_.phase())]}});
}

JointRequest MotionEngine::update(const SensorFrame& frame, const FallState& fall, const MotionRequest& request,
                                  const HeadJointRequest& head, const ArmMotionRequest& arm) {
  info_.motion = request.motion;
  info_.kickDone = request.kickId == doneKickId_;
  JointRequest out;

  // Falling or fallen: drop whatever runs (a running get-up handles its own tilt).
  const bool down = fall.falling || fall.fallen;
  const bool lyingStates = state_ == State::Falling || state_ == State::Lying || state_ == State::GetUp ||
                           state_ == State::PlayDead || state_ == State::Sitting || state_ == State::SitDown;
  if (down && !lyingStates) enter(fall.fallen ? State::Lying : State::Falling, frame);

  switch (state_) {
    case State::Start:
      enter(State::Transition, frame);
      [[fallthrough]];
    case State::Transition: {
      out = interpolate(frame, walk_.standPosture(), params_.transitionTime, 1.0);
      if (frame.time - stateStart_ >= params_.transitionTime) {
        walk_.reset(frame);
        state_ = State::Walk;
      }
      break;
    }
    case State::Walk: {
      Pose2 speed;
      bool stop = true;
      switch (request.motion) {
        case MotionType::Walk: speed = request.walkSpeed; stop = false; break;
        case MotionType::WalkTo:
          if (request.walkTargetId != walkTargetId_) {
            walkTargetId_ = request.walkTargetId;
            walkTarget_ = request.walkTargetInOdometry ? request.walkTarget : odometry_.pose * request.walkTarget;
            walkToStopped_ = false;
          }
          speed = walkToSpeed(walkTarget_, params_.walkToPositionTolerance, params_.walkToAngleTolerance, true);
          stop = speed.x == 0 && speed.y == 0 && speed.theta == 0;
          traceWalkTo(frame, speed, "walk_to");
          break;
        case MotionType::Kick:
          if (request.kickId != doneKickId_) {
            if (request.kickId != kickId_) {
              kickId_ = request.kickId;
              kickLeft_ = request.ballPosition.y() >= 0;
              walkToStopped_ = false;
            }
            // The kick pose: facing the kick direction, the ball in front of the kicking foot.
            const Pose2 pose = kickPose(request.ballPosition, request.kickDirection, kickLeft_);
            speed = walkToSpeed(odometry_.pose * pose, params_.kickPositionTolerance, params_.kickAngleTolerance, false);
            stop = speed.x == 0 && speed.y == 0 && speed.theta == 0;
            traceWalkTo(frame, speed, "kick");
          }
          break;
        default: break;
      }
      out = walk_.update(frame, speed, stop);
      if (walk_.standing()) {
        if (request.motion == MotionType::SitDown) {
          enter(State::SitDown, frame);
        } else if (request.motion == MotionType::PlayDead) {
          enter(State::PlayDead, frame);
        } else if (request.motion == MotionType::Kick && request.kickId == kickId_ && request.kickId != doneKickId_ &&
                   walkToStopped_) {
          kick_.start(frame, walk_.standPosture(), request.ballPosition, request.kickDirection);
          enter(State::Kick, frame);
        }
      }
      break;
    }
    case State::Kick: {
      out = kick_.update(frame);
      if (kick_.done()) {
        doneKickId_ = kickId_;
        walk_.reset(frame);
        state_ = State::Walk;
        stateStart_ = frame.time;
      }
      break;
    }
    case State::Falling: {
      // Held through the impact: "fallen" (48 deg of tilt) comes a few cycles after
      // "falling", well before the robot hits the ground.
      out.position = safeFallPosture(frame.joints.position, fall.direction);
      out.stiffness.fill(0.5);
      if (fall.fallen && (frame.inertial.gyroscope.norm() < 0.5 || frame.time - fall.fallTime > 1.0))
        enter(State::Lying, frame);
      break;
    }
    case State::Lying: {
      out.position = frame.joints.position;
      out.stiffness.fill(0.1);
      const bool settled = frame.time - stateStart_ > 0.5 && frame.inertial.gyroscope.norm() < 0.3;
      if (settled && wantsFeet(request)) {
        getUp_.start(frame, fall.direction, walk_.standPosture());
        enter(State::GetUp, frame);
        ++info_.getUpAttempts;
      } else if (!fall.fallen && !fall.falling && settled) {
        enter(State::Transition, frame);  // upright after all (e.g. caught by a wall)
      }
      break;
    }
    case State::GetUp: {
      out = getUp_.update(frame);
      if (getUp_.done()) {
        walk_.reset(frame);
        enter(State::Walk, frame);
      } else if (getUp_.failed()) {
        enter(State::Lying, frame);
      }
      break;
    }
    case State::SitDown: {
      out = interpolate(frame, sitPosture(walk_.standPosture()), params_.sitDownTime, 0.8);
      if (frame.time - stateStart_ >= params_.sitDownTime) enter(State::Sitting, frame);
      break;
    }
    case State::Sitting: {
      out.position = frame.joints.position;
      out.stiffness.fill(0.15);
      if (wantsFeet(request)) {
        out.stiffness.fill(1.0);
        enter(State::Transition, frame);
        params_.transitionTime = std::max(params_.transitionTime, 0.0);
      }
      break;
    }
    case State::PlayDead: {
      out.position = frame.joints.position;
      out.stiffness.fill(params_.playDeadStiffness);
      if (request.motion != MotionType::PlayDead) {
        if (fall.fallen) enter(State::Lying, frame);
        else if (request.motion == MotionType::SitDown) enter(State::SitDown, frame);
        else enter(State::Transition, frame);
      }
      break;
    }
  }

  const bool headFree = state_ == State::Walk || state_ == State::Transition || state_ == State::Kick ||
                        state_ == State::Sitting || state_ == State::SitDown;
  if (headFree) applyHead(out, head);
  applyArm(out, frame, arm);

  // Odometry: the walk's kinematic odometry while on the feet; the gyro's yaw otherwise.
  walk_.updateOdometry(frame, !(state_ == State::Walk || state_ == State::Transition || state_ == State::Kick));
  odometry_.pose = walk_.odometry();

  info_.stable = state_ == State::Walk;
  info_.walkSpeed = state_ == State::Walk ? walk_.appliedSpeed() : Pose2();
  info_.upright = !(state_ == State::Falling || state_ == State::Lying || state_ == State::GetUp);
  info_.walkToReached = request.motion == MotionType::WalkTo && walkToStopped_ && walk_.standing();
  info_.kickDone = request.kickId == doneKickId_;
  lastOutput_ = out.position;
  return out;
}

}  // namespace nao
