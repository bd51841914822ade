#pragma once
// One image's percepts together, with its camera, exposure time and camera matrix: what the
// camera pipeline publishes (representations/perception/CameraPercepts.h).
// A module of the camera pipeline (perception/vision/CameraPipeline.h), once per image.
#include "perception/CameraModel.h"
#include "perception/vision/VisionTypes.h"
#include "representations/perception/CameraPercepts.h"
#include "representations/perception/CirclePercept.h"
#include "representations/perception/FieldLines.h"
#include "representations/perception/GoalBoxSidePercept.h"
#include "representations/perception/IntersectionsPercept.h"
#include "representations/perception/PenaltyMarkPercept.h"
#include "robot/CameraImage.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class CameraPerceptsProvider
    : public Module<CameraPerceptsProvider,
                    Requires<CameraImage, CameraMatrix, FieldBoundary, ObstaclesPercept, BallPercept, FieldLines,
                             IntersectionsPercept, CirclePercept, PenaltyMarkPercept, GoalBoxSidePercept>,
                    Provides<CameraPercepts>, Cadence::Cognition> {
 public:
  explicit CameraPerceptsProvider(const ModuleContext& context = {});

 private:
  void update() override;
};

}  // namespace nao::modules
