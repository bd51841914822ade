#pragma once
// Detects that the robot is falling or has fallen, from the IMU as a NAO sees it.
// Falling: the torso tilts beyond fallingAngle and keeps tipping (gyro) -- time to go soft.
// Fallen: the tilt exceeds fallenAngle (48 deg), or the feet carry no weight while tilted
// beyond fallingAngle. Stays fallen until the torso has been upright for uprightTime.
#include "representations/perception/FallState.h"
#include "robot/SensorData.h"

namespace nao {

// Which way a torso at this IMU roll and pitch (Ry(pitch) Rx(roll), rad) leans or lies: the
// torso axis (x: front/back, y: sides) that points down most.
FallDirection lyingDirection(double roll, double pitch);

class FallDetector {
 public:
  struct Params {
    double fallingAngle = 0.52;   // rad (30 deg)
    double fallingRate = 0.5;     // rad/s tipping further away from upright
    double fallenAngle = 0.84;    // rad (48 deg)
    double uprightAngle = 0.35;   // rad (20 deg): upright again below this ...
    double uprightTime = 1.0;     // s ... for this long
    double minFootWeight = 0.5;   // kg on both feet together: below it, the feet are off the ground
  };

  FallDetector() = default;
  explicit FallDetector(const Params& params) : params_(params) {}

  const FallState& update(const SensorFrame& frame);
  const FallState& state() const { return state_; }
  void reset() { state_ = {}; uprightSince_ = -1; }

 private:
  Params params_;
  FallState state_;
  double uprightSince_ = -1;
};

}  // namespace nao
