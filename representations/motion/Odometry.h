#pragma once
// Where the robot went (MotionEngine provides it).
#include "robot/math/Pose2.h"

namespace nao {

// The robot's pose in the odometry frame (fixed to the ground where the robot program
// started), from the legs' kinematics, the IMU and the gyro.
struct Odometry {
  Pose2 pose;
};

}  // namespace nao
