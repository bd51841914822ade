#pragma once
// Straight field lines: the segments merged and white-tested, the spots on the circle left out
// (perception/vision/LineDetector.h, fitLines). NAO_LINEDEBUG=1 prints why a candidate was dropped.
// A module of the camera pipeline (perception/vision/CameraPipeline.h), once per image.
#include "perception/CameraModel.h"
#include "perception/vision/VisionTypes.h"
#include "representations/perception/CirclePercept.h"
#include "representations/perception/FieldColourReference.h"
#include "representations/perception/FieldLines.h"
#include "representations/perception/LineSpots.h"
#include "representations/perception/VisionGeometry.h"
#include "robot/CameraImage.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class LinePerceptor : public Module<LinePerceptor,
                                    Requires<LineSpots, CirclePercept, CameraImage, FieldColourReference,
                                             ObstaclesPercept, CameraMatrix, VisionGeometry>,
                                    Provides<FieldLines>, Cadence::Cognition> {
 public:
  explicit LinePerceptor(const ModuleContext& context = {});

 private:
  void update() override;
};

}  // namespace nao::modules
