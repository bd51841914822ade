#include "controllers/modules/FallDetector.h"

#include "robot/ModuleRegistry.h"

namespace nao::modules {

FallDetector::FallDetector(const ModuleContext& context)
    : detector_(context.load<nao::FallDetector::Params>(name())) {}

void FallDetector::update() { out<FallState>() = detector_.update(in<SensorFrame>()); }

NAO_REGISTER_MODULE(FallDetector);

}  // namespace nao::modules
