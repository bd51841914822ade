#include "controllers/modules/HeadControl.h"

#include "robot/ModuleRegistry.h"

namespace nao::modules {

HeadControl::HeadControl(const ModuleContext& context) : head_(context.load<nao::HeadControl::Params>(name())) {}

void HeadControl::update() {
  out<HeadJointRequest>() = head_.update(in<SensorFrame>(), in<HeadMotionRequest>(), in<TorsoState>().robotToTorso);
}

NAO_REGISTER_MODULE(HeadControl);

}  // namespace nao::modules
