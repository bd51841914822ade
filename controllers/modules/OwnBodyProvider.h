#pragma once
// Cognition cadence: the robot's own body (perception/OwnBody.h) at the current image's
// exposure time, from the joints and torso interpolated to its timestamp and the calibrated
// body offset, as ExposureCameraMatrixProvider places the camera. The vision refuses balls on it.
#include "perception/CameraCalibration.h"
#include "perception/OwnBody.h"
#include "representations/infrastructure/CurrentImage.h"
#include "representations/infrastructure/FrameHistory.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class OwnBodyProvider : public Module<OwnBodyProvider, Requires<CurrentImage, FrameHistory, CameraCalibration>,
                                      Provides<OwnBody>, Cadence::Cognition> {
 public:
  // Parameters: config/parameters/OwnBodyProvider.json (OwnBodyParams).
  explicit OwnBodyProvider(const ModuleContext& context = {});

 private:
  void update() override;
  OwnBodyParams params_;
};

}  // namespace nao::modules
