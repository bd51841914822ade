#include "controllers/modules/MotionEngine.h"

#include "robot/ModuleRegistry.h"

namespace nao::modules {

MotionEngine::MotionEngine(const ModuleContext& context) : engine_(context.load<nao::MotionEngine::Params>(name())) {
  engine_.setDebug(context.debug);
}

void MotionEngine::update() {
  out<JointRequest>() =
      engine_.update(in<SensorFrame>(), in<FallState>(), in<MotionRequest>(), in<HeadJointRequest>(),
                     in<ArmMotionRequest>());
  out<MotionInfo>() = engine_.info();
  out<Odometry>() = engine_.odometry();
}

NAO_REGISTER_MODULE(MotionEngine);

}  // namespace nao::modules
