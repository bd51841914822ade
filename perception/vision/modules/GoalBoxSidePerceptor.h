#pragma once
// The goal box seen from the side, in the image alone (perception/vision/GoalBoxDetector.h).
// A module of the camera pipeline (perception/vision/CameraPipeline.h), once per image.
#include "representations/perception/FieldLines.h"
#include "representations/perception/GoalBoxSidePercept.h"
#include "robot/CameraImage.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class GoalBoxSidePerceptor : public Module<GoalBoxSidePerceptor, Requires<FieldLines, CameraImage>,
                                           Provides<GoalBoxSidePercept>, Cadence::Cognition> {
 public:
  explicit GoalBoxSidePerceptor(const ModuleContext& context = {});

 private:
  void update() override;
};

}  // namespace nao::modules
