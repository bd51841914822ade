#pragma once
// A NAO joint servo as the simulator drives it: the motor board's position controller
// (P on the angle error, D on the joint speed) saturated by a DC motor's torque-speed line,
// scaled by the requested stiffness (0 = motor off, no torque).
//
//   torque = stiffness * clamp(kp (target - q) - kd qdot, limit(qdot))
//   limit  = stall (1 - |qdot| / noLoadSpeed)   while the torque drives the motion,
//            stall                             while it brakes it.
//
// The NAO's speed limit needs no separate slew limiter: a servo asked to move far runs at
// saturation along the torque-speed line and cannot exceed the no-load speed, which is the
// documented maximum joint speed. Stall torques come from the model's actuator ctrlrange, the
// no-load speed from the actuator's user[0] when the model gives it (else defaults()' table of
// naoqi's maximum joint speeds); gains from defaults(), one set per joint group.
#include "robot/JointIds.h"

namespace nao::sim {

struct ServoParams {
  double kp = 0;           // N m / rad
  double kd = 0;           // N m s / rad
  double stallTorque = 0;  // N m at the joint (the actuator's ctrlrange)
  double noLoadSpeed = 1;  // rad/s, the joint's maximum speed
};

class ServoModel {
 public:
  // The gains and no-load speed for a LoLA joint with the given stall torque.
  static ServoParams defaults(Joint joint, double stallTorque);
  // The largest torque magnitude the motor gives in the direction of `direction` (its sign)
  // while the joint turns at qdot.
  static double torqueLimit(const ServoParams& p, double qdot, double direction);
  // The joint torque for a position target at the given stiffness (0..1, clamped).
  static double torque(const ServoParams& p, double target, double q, double qdot, double stiffness);
};

}  // namespace nao::sim
