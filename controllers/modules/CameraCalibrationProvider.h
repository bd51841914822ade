#pragma once
// Motion cadence: the camera calibration in use. It starts as the one the program was built with
// (the head's stored calibration: RobotProgramConfig::calibration, as this module's parameter
// "CameraCalibrationProvider") and switches to the calibrator's when its status says it applied
// one (a new appliedId): CameraMatrixProvider uses it from that cycle, the cognition from the
// next image on.
#include "perception/CameraCalibration.h"
#include "representations/perception/CalibrationStatus.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class CameraCalibrationProvider
    : public Module<CameraCalibrationProvider, Requires<CalibrationStatus>, Provides<CameraCalibration>> {
 public:
  explicit CameraCalibrationProvider(const ModuleContext& context = {});

 private:
  void update() override;

  CameraCalibration current_;
  int appliedId_ = 0;
};

}  // namespace nao::modules
