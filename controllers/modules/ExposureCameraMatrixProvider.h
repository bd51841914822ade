#pragma once
// Cognition cadence: the current image's camera matrix at its exposure time, from the joints
// and torso interpolated to the image's timestamp (a head turning at 3 rad/s moves 1.7 deg in
// the 10 ms between a motion cycle and an exposure), the calibration's offsets and the
// intrinsics of the image's own size.
#include "perception/CameraCalibration.h"
#include "representations/infrastructure/CurrentImage.h"
#include "representations/infrastructure/FrameHistory.h"
#include "representations/perception/ImageCameraMatrix.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class ExposureCameraMatrixProvider
    : public Module<ExposureCameraMatrixProvider, Requires<CurrentImage, FrameHistory, CameraCalibration>,
                    Provides<ImageCameraMatrix>, Cadence::Cognition> {
 public:
  explicit ExposureCameraMatrixProvider(const ModuleContext& = {}) {}

 private:
  void update() override;
};

}  // namespace nao::modules
