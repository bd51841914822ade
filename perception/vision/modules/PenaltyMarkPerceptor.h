#pragma once
// The penalty mark, clear of the lines and the ball (perception/vision/PenaltyMarkDetector.h).
// A module of the camera pipeline (perception/vision/CameraPipeline.h), once per image.
#include "perception/CameraModel.h"
#include "perception/vision/VisionTypes.h"
#include "representations/perception/FieldColourReference.h"
#include "representations/perception/FieldLines.h"
#include "representations/perception/PenaltyMarkPercept.h"
#include "representations/perception/VisionGeometry.h"
#include "robot/CameraImage.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class PenaltyMarkPerceptor : public Module<PenaltyMarkPerceptor,
                                           Requires<CameraImage, ScanLineRegions, FieldColourReference, FieldLines,
                                                    ObstaclesPercept, CameraMatrix, VisionGeometry, BallPercept>,
                                           Provides<PenaltyMarkPercept>, Cadence::Cognition> {
 public:
  explicit PenaltyMarkPerceptor(const ModuleContext& context = {});

 private:
  void update() override;
};

}  // namespace nao::modules
