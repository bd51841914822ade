#include "controllers/StandController.h"

#include <algorithm>

namespace nao {

JointArray StandController::standPosture() {
  JointArray p{};
  p[HeadYaw] = 0;
  p[HeadPitch] = 0;
  // Legs: hip, knee and ankle pitch sum to zero so the soles are parallel to the torso's
  // xy plane; the knees are bent like a NAO's stand (lower centre of mass, knees unlocked).
  p[LHipYawPitch] = 0;
  p[LHipRoll] = p[RHipRoll] = 0;
  p[LHipPitch] = p[RHipPitch] = -0.45;
  p[LKneePitch] = p[RKneePitch] = 0.9;
  p[LAnklePitch] = p[RAnklePitch] = -0.45;
  p[LAnkleRoll] = p[RAnkleRoll] = 0;
  // Arms down at the sides, elbows nearly straight.
  p[LShoulderPitch] = p[RShoulderPitch] = 1.57;
  p[LShoulderRoll] = 0.1;
  p[RShoulderRoll] = -0.1;
  p[LElbowYaw] = -1.57;
  p[RElbowYaw] = 1.57;
  p[LElbowRoll] = -0.05;
  p[RElbowRoll] = 0.05;
  p[LWristYaw] = p[RWristYaw] = 0;
  p[LHand] = p[RHand] = 0;
  return p;
}

JointRequest StandController::update(const SensorFrame& frame, const FallState& fall) {
  JointRequest request;
  if (fall.falling || fall.fallen) {
    // Safe fall: soft joints that stay where they are.
    request.position = frame.joints.position;
    request.stiffness.fill(params_.fallStiffness);
    started_ = false;
    return request;
  }
  if (!started_) {
    started_ = true;
    startTime_ = frame.time;
    startPosition_ = frame.joints.position;
  }
  const double t = params_.softStartTime > 0 ? std::clamp((frame.time - startTime_) / params_.softStartTime, 0.0, 1.0) : 1.0;
  const double s = t * t * (3 - 2 * t);  // smoothstep: no jerk at either end
  const JointArray goal = standPosture();
  for (int j = 0; j < NumJoints; ++j) request.position[j] = startPosition_[j] + s * (goal[j] - startPosition_[j]);
  // Leaning forward (pitch > 0) rotates the feet toes-up relative to the shins: pressing the
  // toes down (a larger AnklePitch target) pushes the body back; likewise for roll.
  const double roll = frame.inertial.angle.x(), pitch = frame.inertial.angle.y();
  request.position[LAnklePitch] += s * params_.ankleGain * pitch;
  request.position[RAnklePitch] += s * params_.ankleGain * pitch;
  request.position[LAnkleRoll] += s * params_.ankleGain * roll;
  request.position[RAnkleRoll] += s * params_.ankleGain * roll;
  request.stiffness.fill(params_.stiffness);
  return request;
}

}  // namespace nao
