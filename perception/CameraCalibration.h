#pragma once
// The six extrinsic offsets the autonomous calibration estimates (see docs/conventions.md).
// Yaw and translations are not calibrated: with no global reference a yaw offset is
// indistinguishable from the robot's own heading, and translational mount errors of a few
// millimetres move a projected point far less than 0.1 deg of rotation does.
#include <array>
#include <string>

namespace nao {

struct CameraCalibration {
  double bodyRoll = 0, bodyPitch = 0;      // rad
  double topRoll = 0, topPitch = 0;        // rad
  double bottomRoll = 0, bottomPitch = 0;  // rad

  static constexpr std::array<const char*, 6> kNames = {"body_roll", "body_pitch", "top_roll",
                                                        "top_pitch", "bottom_roll", "bottom_pitch"};
  std::array<double, 6> toArray() const { return {bodyRoll, bodyPitch, topRoll, topPitch, bottomRoll, bottomPitch}; }
  static CameraCalibration fromArray(const std::array<double, 6>& a) {
    return {a[0], a[1], a[2], a[3], a[4], a[5]};
  }
};

}  // namespace nao
