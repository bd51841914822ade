#pragma once
// The ball: candidates from the regions, verified by their outline and the ball classifier
// (perception/vision/BallDetector.h, models/vision/ball_classifier.yml); none on the robot's
// own body. A noisy image is read blurred (ImageDenoiser).
// A module of the camera pipeline (perception/vision/CameraPipeline.h), once per image.
#include "perception/CameraModel.h"
#include "perception/OwnBody.h"
#include "perception/vision/VisionTypes.h"
#include "representations/perception/DenoisedImage.h"
#include "representations/perception/FieldColourReference.h"
#include "representations/perception/VisionGeometry.h"
#include "robot/CameraImage.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class BallPerceptor
    : public Module<
          BallPerceptor,
          Requires<CameraImage, DenoisedImage, ScanLineRegions, FieldColourReference, ObstaclesPercept, CameraMatrix, VisionGeometry,
                   OwnBody>,
          Provides<BallPercept>, Cadence::Cognition> {
 public:
  explicit BallPerceptor(const ModuleContext& context = {});

 private:
  void update() override;
};

}  // namespace nao::modules
