#pragma once
// The body: the behaviour's MotionRequest -> joint requests (stand, walk, kick, get up, ...),
// the odometry and what the motion does (controllers/MotionEngine.h does the work).
#include "controllers/MotionEngine.h"
#include "controllers/modules/MotionEngineParams.h"
#include "representations/behavior/ArmMotionRequest.h"
#include "representations/behavior/MotionRequest.h"
#include "representations/motion/HeadJointRequest.h"
#include "representations/motion/MotionInfo.h"
#include "representations/motion/Odometry.h"
#include "representations/perception/FallState.h"
#include "robot/JointRequest.h"
#include "robot/Module.h"
#include "robot/Parameters.h"
#include "robot/SensorData.h"

namespace nao::modules {

class MotionEngine : public Module<MotionEngine, Requires<SensorFrame, FallState, MotionRequest, HeadJointRequest, ArmMotionRequest>,
                                   Provides<JointRequest, MotionInfo, Odometry>> {
 public:
  explicit MotionEngine(const ModuleContext& context = {});
  const nao::MotionEngine& engine() const { return engine_; }

 private:
  void update() override;

  nao::MotionEngine engine_;
};

}  // namespace nao::modules
