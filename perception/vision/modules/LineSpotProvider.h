#pragma once
// Line spots, their chains and straight segments from the white regions; nothing inside the
// ball's disc (perception/vision/LineDetector.h, findLineCandidates). Spots are measured on the
// pixels the regions came from (the blurred copy of a noisy image).
// A module of the camera pipeline (perception/vision/CameraPipeline.h), once per image.
#include "perception/CameraModel.h"
#include "perception/vision/VisionTypes.h"
#include "representations/perception/DenoisedImage.h"
#include "representations/perception/FieldColourReference.h"
#include "representations/perception/LineSpots.h"
#include "representations/perception/VisionGeometry.h"
#include "robot/CameraImage.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class LineSpotProvider : public Module<LineSpotProvider,
                                       Requires<CameraImage, DenoisedImage, ScanLineRegions, FieldColourReference, ObstaclesPercept,
                                                CameraMatrix, VisionGeometry, BallPercept>,
                                       Provides<LineSpots>, Cadence::Cognition> {
 public:
  explicit LineSpotProvider(const ModuleContext& context = {});

 private:
  void update() override;
};

}  // namespace nao::modules
