#pragma once
// The behaviour's arm request, laid over whatever the legs do: a raised arm is how a robot
// reports in the Autonomous Calibration Challenge (with speech). The motion engine raises it
// only while the robot stands, and lowers it for anything else.
namespace nao {

struct ArmMotionRequest {
  enum class Arm { None, Left, Right };
  Arm raise = Arm::None;
};

}  // namespace nao
