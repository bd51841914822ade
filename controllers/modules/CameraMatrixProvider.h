#pragma once
// Both cameras' calibrated matrices: head kinematics on the torso pose, with the camera
// calibration's offsets and the intrinsics of the resolution each camera delivers.
#include <array>

#include "perception/CameraCalibration.h"
#include "perception/CameraModel.h"
#include "representations/infrastructure/CameraImages.h"
#include "representations/perception/CameraMatrices.h"
#include "representations/perception/TorsoState.h"
#include "robot/Module.h"
#include "robot/Parameters.h"
#include "robot/SensorData.h"

namespace nao::modules {

class CameraMatrixProvider
    : public Module<CameraMatrixProvider, Requires<SensorFrame, TorsoState, CameraCalibration, CameraImages>,
                    Provides<CameraMatrices>> {
 public:
  explicit CameraMatrixProvider(const ModuleContext& = {}) {}
  // The intrinsics in use: nominal until a camera delivers an image of another size.
  const std::array<CameraIntrinsics, kNumCameras>& intrinsics() const { return intrinsics_; }

 private:
  void update() override;

  // The module's own state (it used to be written back into the program's configuration).
  std::array<CameraIntrinsics, kNumCameras> intrinsics_{CameraIntrinsics::nominal(CameraId::Top),
                                                        CameraIntrinsics::nominal(CameraId::Bottom)};
};

}  // namespace nao::modules
