#include "controllers/modules/TorsoMatrixProvider.h"

#include "robot/ForwardKinematics.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

void TorsoMatrixProvider::update() {
  const SensorFrame& frame = in<SensorFrame>();
  out<TorsoState>().robotToTorso = robotToTorso(frame.joints.position, frame.inertial.angle.x(), frame.inertial.angle.y());
}

NAO_REGISTER_MODULE(TorsoMatrixProvider);

}  // namespace nao::modules
