#pragma once
// What the robot program asks of the joints every cycle (LoLA's actuator packet).
#include <array>

#include "robot/JointIds.h"

namespace nao {

struct JointRequest {
  JointArray position{};   // rad, LoLA order
  JointArray stiffness{};  // 0..1; 0 = soft (the motor exerts no torque)
};

struct LedRequest {
  std::array<double, 3> chest{};
  std::array<double, 10> leftEar{}, rightEar{};
  std::array<double, 24> leftEye{}, rightEye{};
  std::array<double, 3> leftFoot{}, rightFoot{};
  std::array<double, 12> skull{};
};

}  // namespace nao
