#pragma once
// What a NAO reports every 12 ms cycle (LoLA's sensor packet), as plain representations.
#include <array>
#include <cstdint>
#include <string>

#include <Eigen/Core>

#include "robot/JointIds.h"

namespace nao {

struct JointSensorData {
  JointArray position{};     // rad
  JointArray stiffness{};    // 0..1
  JointArray current{};      // A
  JointArray temperature{};  // deg C
};

struct InertialSensorData {
  Eigen::Vector3d accelerometer = Eigen::Vector3d::Zero();  // m/s^2, torso frame
  Eigen::Vector3d gyroscope = Eigen::Vector3d::Zero();      // rad/s, torso frame
  // Torso roll (x) and pitch (y) from the IMU's filter, rad. The torso orientation is
  // Ry(pitch) * Rx(roll) once yaw is removed (ZYX Euler angles).
  Eigen::Vector2d angle = Eigen::Vector2d::Zero();
};

struct FsrSensorData {
  std::array<double, NumFsr> weight{};  // kg per sensor, LoLA order
  double total(bool left) const {
    double s = 0;
    for (int i = left ? 0 : 4; i < (left ? 4 : 8); ++i) s += weight[i];
    return s;
  }
};

struct BatteryData {
  double charge = 1.0;  // 0..1
  double status = 0;
  double current = 0;
  double temperature = 0;
};

struct RobotInfo {
  std::string bodyId = "sim-body";
  std::string headId = "sim-head";
  std::string bodyVersion = "V6";
  std::string headVersion = "V6";
};

// One sensor frame. time is the backend's clock in seconds (simulated time in the simulator).
struct SensorFrame {
  double time = 0;
  std::uint64_t cycle = 0;
  JointSensorData joints;
  InertialSensorData inertial;
  FsrSensorData fsr;
  std::array<double, NumTouch> touch{};
  std::array<double, 2> sonar{};
  BatteryData battery;
};

}  // namespace nao
