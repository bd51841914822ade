#pragma once
// L, T and X intersections of the field lines (perception/vision/IntersectionDetector.h).
// A module of the camera pipeline (perception/vision/CameraPipeline.h), once per image.
#include "perception/CameraModel.h"
#include "perception/vision/VisionTypes.h"
#include "representations/perception/FieldColourReference.h"
#include "representations/perception/FieldLines.h"
#include "representations/perception/IntersectionsPercept.h"
#include "robot/CameraImage.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class IntersectionPerceptor
    : public Module<IntersectionPerceptor,
                    Requires<FieldLines, CameraMatrix, ObstaclesPercept, CameraImage, FieldColourReference>,
                    Provides<IntersectionsPercept>, Cadence::Cognition> {
 public:
  explicit IntersectionPerceptor(const ModuleContext& context = {});

 private:
  void update() override;
};

}  // namespace nao::modules
