#pragma once
// The robot program: a pipeline of modules over a blackboard, run once per 12 ms cycle
// against any Backend. The same code runs in the simulator and on the NAO. Which module
// provides what comes from config/modules.json, each module's parameters from
// config/parameters/<module>.json (docs/architecture.md).
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "controllers/MotionEngine.h"
#include "perception/CameraCalibration.h"
#include "representations/behavior/HeadMotionRequest.h"
#include "representations/behavior/MotionRequest.h"
#include "representations/infrastructure/CameraImages.h"
#include "representations/motion/HeadJointRequest.h"
#include "representations/motion/MotionInfo.h"
#include "representations/motion/Odometry.h"
#include "representations/perception/CameraMatrices.h"
#include "representations/perception/FallState.h"
#include "representations/perception/TorsoState.h"
#include "robot/Backend.h"
#include "robot/Blackboard.h"
#include "robot/Module.h"

namespace nao {

struct RobotProgramConfig {
  CameraCalibration calibration;  // loaded per robot (head id) at start
  // Walk, kick, get-up parameters instead of config/parameters/MotionEngine.json (a scenario's
  // trial parameters); unset: the files.
  std::optional<MotionEngine::Params> motion;
  // Holds modules.json, parameters/ and robots/<head id>/. Empty: config/modules.json of the
  // data root and every module with its compiled-in defaults (no parameter files).
  std::string configDir = defaultConfigDir();
  std::string headId;  // selects config/robots/<head id>/ overlays; empty: none
  // Representation -> module, replacing config/modules.json's entries (e.g. an oracle).
  std::map<std::string, std::string> providers;

  static std::string defaultConfigDir();
};

class RobotProgram {
 public:
  // Throws nao::Error for a bad config/modules.json or parameter file (file and key named).
  explicit RobotProgram(const RobotProgramConfig& config = {});
  // One cycle: sensors and images in, modules, joint request out. False when the backend
  // stopped (its stopReason says why).
  bool cycle(Backend& backend);

  const Blackboard& blackboard() const { return blackboard_; }
  Blackboard& blackboard() { return blackboard_; }
  std::vector<std::string> moduleOrder() const { return pipeline_.order(); }
  const Pipeline& pipeline() const { return pipeline_; }

 private:
  Blackboard blackboard_;
  Pipeline pipeline_;
};

}  // namespace nao
