#include "controllers/modules/TorsoMatrixProvider.h"

#include "robot/ForwardKinematics.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

void TorsoMatrixProvider::update() {
  out<TorsoState>().robotToTorso = robotToTorso(in<SensorFrame>());
}

NAO_REGISTER_MODULE(TorsoMatrixProvider);

}  // namespace nao::modules
