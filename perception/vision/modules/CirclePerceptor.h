#pragma once
// The centre circle from the line spots (perception/vision/CircleDetector.h); the spots on it
// are no line.
// A module of the camera pipeline (perception/vision/CameraPipeline.h), once per image.
#include "perception/CameraModel.h"
#include "perception/vision/VisionTypes.h"
#include "representations/perception/CirclePercept.h"
#include "representations/perception/FieldColourReference.h"
#include "representations/perception/LineSpots.h"
#include "representations/perception/VisionGeometry.h"
#include "robot/CameraImage.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class CirclePerceptor
    : public Module<
          CirclePerceptor,
          Requires<LineSpots, CameraImage, FieldColourReference, ObstaclesPercept, CameraMatrix, VisionGeometry>,
          Provides<CirclePercept>, Cadence::Cognition> {
 public:
  explicit CirclePerceptor(const ModuleContext& context = {});

 private:
  void update() override;
};

}  // namespace nao::modules
