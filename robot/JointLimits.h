#pragma once
// The NAO V6's joint limits in degrees, LoLA order (../shared/reference/nao-v6.md): the one
// table that kinematics and the command line's bounds on head angles read.
#include <array>

#include "robot/JointIds.h"

namespace nao {

struct JointLimitDeg {
  double min, max;
};

inline constexpr std::array<JointLimitDeg, NumJoints> kJointLimitsDeg = {{
    {-119.5, 119.5},  // HeadYaw
    {-38.5, 29.5},    // HeadPitch
    {-119.5, 119.5},  // LShoulderPitch
    {-18, 76},        // LShoulderRoll
    {-119.5, 119.5},  // LElbowYaw
    {-88.5, -2},      // LElbowRoll
    {-104.5, 104.5},  // LWristYaw
    {-65.62, 42.44},  // LHipYawPitch
    {-21.74, 45.29},  // LHipRoll
    {-88, 27.73},     // LHipPitch
    {-5.29, 121.04},  // LKneePitch
    {-68.15, 52.86},  // LAnklePitch
    {-22.79, 44.06},  // LAnkleRoll
    {-45.29, 21.74},  // RHipRoll
    {-88, 27.73},     // RHipPitch
    {-5.90, 121.47},  // RKneePitch
    {-67.97, 53.40},  // RAnklePitch
    {-44.06, 22.80},  // RAnkleRoll
    {-119.5, 119.5},  // RShoulderPitch
    {-76, 18},        // RShoulderRoll
    {-119.5, 119.5},  // RElbowYaw
    {2, 88.5},        // RElbowRoll
    {-104.5, 104.5},  // RWristYaw
    {0, 0},  // LHand: not an angle (LoLA's 0..1 opening; Kinematics.cpp)
    {0, 0},  // RHand
}};

}  // namespace nao
