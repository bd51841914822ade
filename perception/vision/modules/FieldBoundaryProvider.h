#pragma once
// Where the field ends in the image (perception/vision/FieldBoundaryDetector.h).
// A module of the camera pipeline (perception/vision/CameraPipeline.h), once per image.
#include "perception/CameraModel.h"
#include "perception/vision/VisionTypes.h"
#include "representations/perception/UncutScanLineRegions.h"
#include "robot/CameraImage.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class FieldBoundaryProvider
    : public Module<FieldBoundaryProvider, Requires<CameraImage, UncutScanLineRegions, CameraMatrix>,
                    Provides<FieldBoundary>, Cadence::Cognition> {
 public:
  explicit FieldBoundaryProvider(const ModuleContext& context = {});

 private:
  void update() override;
};

}  // namespace nao::modules
