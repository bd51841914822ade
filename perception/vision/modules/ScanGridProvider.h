#pragma once
// Where the scan lines lie in this image, from its camera matrix (perception/vision/ScanGrid.h).
// A module of the camera pipeline (perception/vision/CameraPipeline.h), once per image.
#include "perception/CameraModel.h"
#include "perception/vision/ScanGrid.h"
#include "representations/perception/VisionGeometry.h"
#include "robot/CameraImage.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class ScanGridProvider : public Module<ScanGridProvider, Requires<CameraImage, CameraMatrix, VisionGeometry>,
                                       Provides<ScanGrid>, Cadence::Cognition> {
 public:
  explicit ScanGridProvider(const ModuleContext& context = {});

 private:
  void update() override;
};

}  // namespace nao::modules
