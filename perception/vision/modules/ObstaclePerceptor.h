#pragma once
// Image regions of other robots (perception/vision/ObstacleDetector.h).
// A module of the camera pipeline (perception/vision/CameraPipeline.h), once per image.
#include "perception/CameraModel.h"
#include "perception/vision/VisionTypes.h"
#include "robot/CameraImage.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class ObstaclePerceptor
    : public Module<ObstaclePerceptor, Requires<CameraImage, ScanLineRegions, FieldBoundary, CameraMatrix>,
                    Provides<ObstaclesPercept>, Cadence::Cognition> {
 public:
  explicit ObstaclePerceptor(const ModuleContext& context = {});

 private:
  void update() override;
};

}  // namespace nao::modules
