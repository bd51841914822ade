#pragma once
// The robot program: a pipeline of modules over a blackboard, run once per 12 ms cycle
// against any Backend. The same code runs in the simulator and on the NAO.
#include <string>
#include <vector>

#include "controllers/MotionEngine.h"
#include "controllers/Representations.h"
#include "perception/CameraCalibration.h"
#include "robot/Backend.h"
#include "robot/Blackboard.h"
#include "robot/Module.h"

namespace nao {

struct RobotProgramConfig {
  CameraCalibration calibration;  // loaded per robot (head id) at start
  std::array<CameraIntrinsics, kNumCameras> intrinsics{CameraIntrinsics::nominal(CameraId::Top),
                                                       CameraIntrinsics::nominal(CameraId::Bottom)};
  MotionEngine::Params motion;  // walk, kick, get-up parameters
};

class RobotProgram {
 public:
  explicit RobotProgram(const RobotProgramConfig& config = {});
  // One cycle: sensors and images in, modules, joint request out. False when the backend
  // stopped (its stopReason says why).
  bool cycle(Backend& backend);

  const Blackboard& blackboard() const { return blackboard_; }
  Blackboard& blackboard() { return blackboard_; }
  std::vector<std::string> moduleOrder() const { return pipeline_.order(); }

 private:
  Blackboard blackboard_;
  Pipeline pipeline_;
};

}  // namespace nao
