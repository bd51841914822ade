#include "sim/ServoModel.h"

#include <algorithm>
#include <cmath>

namespace nao::sim {

namespace {

// Maximum joint speeds (rad/s) as naoqi reports them for the NAO V6: they are the no-load
// speeds of the motor through its gear (8300 rpm / 130.85 = 6.4 rad/s, / 201.3 = 4.16 rad/s).
constexpr double kSpeedHeadYaw = 8.27, kSpeedHeadPitch = 7.19;
constexpr double kSpeedShoulderPitch = 8.27, kSpeedShoulderRoll = 7.19;
constexpr double kSpeedElbowYaw = 8.27, kSpeedElbowRoll = 7.19, kSpeedWristYaw = 24.6, kSpeedHand = 8.33;
constexpr double kSpeedLegFast = 6.40;  // HipPitch, KneePitch, AnklePitch (gear 130.85)
constexpr double kSpeedLegSlow = 4.16;  // HipYawPitch, HipRoll, AnkleRoll (gear 201.3)

// Gains. The model's joints carry the reflected rotor inertia (armature) and a little
// viscous damping; with those, these gains hold the standing robot to a few tenths of a
// degree, settle a step without overshoot worth mentioning and stay well inside the
// stability limit of the explicit 2 ms step (kp dt^2 / I << 1, kd dt / I < 1).
struct Gains {
  double kp, kd;
};
constexpr Gains kLegGains{60.0, 0.6};
constexpr Gains kArmGains{20.0, 0.15};
constexpr Gains kHeadGains{10.0, 0.08};
constexpr Gains kWristGains{5.0, 0.03};  // the hand's small inertia about the forearm axis
constexpr Gains kHandGains{2.0, 0.01};

}  // namespace

ServoParams ServoModel::defaults(Joint joint, double stallTorque) {
  ServoParams p;
  p.stallTorque = stallTorque;
  Gains g = kArmGains;
  switch (joint) {
    case HeadYaw: g = kHeadGains; p.noLoadSpeed = kSpeedHeadYaw; break;
    case HeadPitch: g = kHeadGains; p.noLoadSpeed = kSpeedHeadPitch; break;
    case LShoulderPitch: case RShoulderPitch: p.noLoadSpeed = kSpeedShoulderPitch; break;
    case LShoulderRoll: case RShoulderRoll: p.noLoadSpeed = kSpeedShoulderRoll; break;
    case LElbowYaw: case RElbowYaw: p.noLoadSpeed = kSpeedElbowYaw; break;
    case LElbowRoll: case RElbowRoll: p.noLoadSpeed = kSpeedElbowRoll; break;
    case LWristYaw: case RWristYaw: g = kWristGains; p.noLoadSpeed = kSpeedWristYaw; break;
    case LHand: case RHand: g = kHandGains; p.noLoadSpeed = kSpeedHand; break;
    case LHipPitch: case RHipPitch: case LKneePitch: case RKneePitch: case LAnklePitch: case RAnklePitch:
      g = kLegGains; p.noLoadSpeed = kSpeedLegFast; break;
    case LHipYawPitch: case LHipRoll: case RHipRoll: case LAnkleRoll: case RAnkleRoll:
      g = kLegGains; p.noLoadSpeed = kSpeedLegSlow; break;
    case NumJoints: break;
  }
  p.kp = g.kp;
  p.kd = g.kd;
  return p;
}

double ServoModel::torqueLimit(const ServoParams& p, double qdot, double direction) {
  if (direction * qdot <= 0) return p.stallTorque;  // braking or at rest: the full stall torque
  return p.stallTorque * std::max(0.0, 1.0 - std::abs(qdot) / p.noLoadSpeed);
}

double ServoModel::torque(const ServoParams& p, double target, double q, double qdot, double stiffness) {
  stiffness = std::clamp(stiffness, 0.0, 1.0);
  if (stiffness == 0) return 0;
  const double command = p.kp * (target - q) - p.kd * qdot;
  const double limit = torqueLimit(p, qdot, command);
  return stiffness * std::clamp(command, -limit, limit);
}

}  // namespace nao::sim
