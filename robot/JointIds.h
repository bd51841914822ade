#pragma once
// Joint ids in LoLA order (NAO V6). RHipYawPitch does not exist on the robot: the left
// and right HipYawPitch are one motor, so the robot program sees only LHipYawPitch.
#include <array>
#include <string_view>

namespace nao {

enum Joint : int {
  HeadYaw, HeadPitch,
  LShoulderPitch, LShoulderRoll, LElbowYaw, LElbowRoll, LWristYaw,
  LHipYawPitch, LHipRoll, LHipPitch, LKneePitch, LAnklePitch, LAnkleRoll,
  RHipRoll, RHipPitch, RKneePitch, RAnklePitch, RAnkleRoll,
  RShoulderPitch, RShoulderRoll, RElbowYaw, RElbowRoll, RWristYaw,
  LHand, RHand,
  NumJoints
};

inline constexpr std::array<std::string_view, NumJoints> kJointNames = {
    "HeadYaw", "HeadPitch",
    "LShoulderPitch", "LShoulderRoll", "LElbowYaw", "LElbowRoll", "LWristYaw",
    "LHipYawPitch", "LHipRoll", "LHipPitch", "LKneePitch", "LAnklePitch", "LAnkleRoll",
    "RHipRoll", "RHipPitch", "RKneePitch", "RAnklePitch", "RAnkleRoll",
    "RShoulderPitch", "RShoulderRoll", "RElbowYaw", "RElbowRoll", "RWristYaw",
    "LHand", "RHand"};

using JointArray = std::array<double, NumJoints>;

// Touch sensors in LoLA order (the "Touch" array).
enum Touch : int {
  ChestButton, HeadFront, HeadMiddle, HeadRear,
  LFootLeft, LFootRight, LHandBack, LHandLeft, LHandRight,
  RFootLeft, RFootRight, RHandBack, RHandLeft, RHandRight,
  NumTouch
};

// FSRs in LoLA order: left foot FL, FR, RL, RR, then the right foot the same.
enum Fsr : int { LFsrFL, LFsrFR, LFsrRL, LFsrRR, RFsrFL, RFsrFR, RFsrRL, RFsrRR, NumFsr };

}  // namespace nao
