#pragma once
// NAO V6 dimensions (metres, radians) from ../shared/reference/nao-v6.md, in the frames of
// docs/conventions.md: the torso origin is the midpoint between the hip joints.
#include <numbers>

namespace nao::dims {

inline constexpr double kDeg = std::numbers::pi / 180.0;

// Head chain: HeadYaw (z) then HeadPitch (y), both at this point of the torso frame.
inline constexpr double kNeckZ = 0.2115;

// Arms: shoulders at (0, +-kShoulderY, kShoulderZ); ShoulderPitch (y), ShoulderRoll (z).
inline constexpr double kShoulderY = 0.098;
inline constexpr double kShoulderZ = 0.185;
inline constexpr double kUpperArmLength = 0.105;    // along x to ElbowYaw (x)
inline constexpr double kElbowOffsetY = 0.015;      // elbow y offset (mirrored on the right)
inline constexpr double kLowerArmLength = 0.05595;  // ElbowRoll (z) to WristYaw (x)
inline constexpr double kHandOffsetX = 0.05775;
inline constexpr double kHandOffsetZ = 0.01231;

// Legs: hips at (0, +-kHipY, 0). HipYawPitch axis (0, 1, -1)/sqrt2 left, (0, 1, 1)/sqrt2 right.
inline constexpr double kHipY = 0.05;
inline constexpr double kThighLength = 0.1;
inline constexpr double kTibiaLength = 0.1029;
inline constexpr double kFootHeight = 0.04519;  // ankle to sole
inline constexpr double kLegLength = kThighLength + kTibiaLength + kFootHeight;  // 0.24809

// Sole rectangle relative to the point below the ankle (left foot; mirror y for the right).
inline constexpr double kSoleFront = 0.1;
inline constexpr double kSoleBack = 0.05;
inline constexpr double kSoleInner = 0.03877;  // towards the other foot
inline constexpr double kSoleOuter = 0.05002;

// The force sensors under the left sole (x forward, y left, m, in the sole frame), in LoLA order:
// front-left, front-right, rear-left, rear-right. The right foot's are these mirrored (y -> -y,
// left and right swapped).
inline constexpr double kFsrX[4] = {0.07025, 0.07025, -0.03025, -0.02965};
inline constexpr double kFsrY[4] = {0.0299, -0.0231, 0.0299, -0.0191};
// Sensor i of 8 (LoLA order: left foot, then right) in its sole's frame, x and y.
inline constexpr double fsrX(int i) { return i < 4 ? kFsrX[i] : kFsrX[(i - 4) ^ 1]; }
inline constexpr double fsrY(int i) { return i < 4 ? kFsrY[i] : -kFsrY[(i - 4) ^ 1]; }

// Cameras, in the HeadPitch joint frame; "pitched down by a" is Ry(a).
inline constexpr double kTopCameraX = 0.05871, kTopCameraZ = 0.06364;
inline constexpr double kTopCameraPitch = 1.2 * kDeg;
inline constexpr double kBottomCameraX = 0.05071, kBottomCameraZ = 0.01774;
inline constexpr double kBottomCameraPitch = 39.7 * kDeg;

// Vertical field of view of both cameras (SoftBank); square pixels.
inline constexpr double kCameraFovY = 43.7 * kDeg;
inline constexpr int kTopWidth = 640, kTopHeight = 480;
inline constexpr int kBottomWidth = 320, kBottomHeight = 240;

// IMU in the torso frame.
inline constexpr double kImuX = -0.008, kImuY = 0.00606, kImuZ = 0.112;

}  // namespace nao::dims
