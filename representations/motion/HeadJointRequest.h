#pragma once
// The head joints HeadControl asks for; the motion engine applies them when the motion allows.

namespace nao {

struct HeadJointRequest {
  double yaw = 0, pitch = 0;  // rad
  double stiffness = 0.8;
};

}  // namespace nao
