#pragma once
// The torso's pose in the robot frame (IMU roll and pitch, leg kinematics): what the camera
// matrices and head control build on.
#include "representations/perception/TorsoState.h"
#include "robot/Module.h"
#include "robot/Parameters.h"
#include "robot/SensorData.h"

namespace nao::modules {

class TorsoMatrixProvider : public Module<TorsoMatrixProvider, Requires<SensorFrame>, Provides<TorsoState>> {
 public:
  explicit TorsoMatrixProvider(const ModuleContext& = {}) {}

 private:
  void update() override;
};

}  // namespace nao::modules
