#include "controllers/FallDetector.h"

#include <algorithm>
#include <cmath>

namespace nao {

// The torso orientation is Ry(pitch) Rx(roll): pitch > 0 leans forward, roll > 0 lifts the
// left side, i.e. leans to the right. Which way the robot lies follows from which torso axis
// points down most: x (front, back) or y (sides). Beyond 90 deg of tilt the two angles alone
// mislead (lying on the face with the hips up reads as a roll of ~180 deg), the axes do not.
FallDirection lyingDirection(double roll, double pitch) {
  const double xUp = -std::sin(pitch);                 // the torso x axis' upward component
  const double yUp = std::sin(roll) * std::cos(pitch);  // the torso y axis' upward component
  if (std::abs(xUp) >= std::abs(yUp)) return xUp < 0 ? FallDirection::Front : FallDirection::Back;
  return yUp > 0 ? FallDirection::Right : FallDirection::Left;
}

const FallState& FallDetector::update(const SensorFrame& frame) {
  const double roll = frame.inertial.angle.x(), pitch = frame.inertial.angle.y();
  // Tilt of the torso's z axis from the vertical, and how fast it grows.
  const double tilt = std::acos(std::clamp(std::cos(roll) * std::cos(pitch), -1.0, 1.0));
  const double rollRate = frame.inertial.gyroscope.x(), pitchRate = frame.inertial.gyroscope.y();
  const double tipping = (roll * rollRate + pitch * pitchRate) / std::max(1e-6, std::hypot(roll, pitch));
  const double footWeight = frame.fsr.total(true) + frame.fsr.total(false);

  if (state_.fallen) {
    if (tilt < params_.uprightAngle) {
      if (uprightSince_ < 0) uprightSince_ = frame.time;
      if (frame.time - uprightSince_ >= params_.uprightTime) reset();
    } else {
      uprightSince_ = -1;
    }
    return state_;
  }
  const bool down = tilt > params_.fallenAngle || (tilt > params_.fallingAngle && footWeight < params_.minFootWeight);
  if (down) {
    state_.fallen = true;
    state_.falling = false;
    state_.fallTime = frame.time;
    state_.direction = lyingDirection(roll, pitch);
    uprightSince_ = -1;
  } else {
    state_.falling = tilt > params_.fallingAngle && tipping > params_.fallingRate;
    state_.direction = state_.falling ? lyingDirection(roll, pitch) : FallDirection::None;
  }
  return state_;
}

}  // namespace nao
