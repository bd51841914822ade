#include "perception/vision/modules/GoalBoxSidePerceptor.h"

#include "perception/vision/GoalBoxDetector.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

GoalBoxSidePerceptor::GoalBoxSidePerceptor(const ModuleContext&) {}

void GoalBoxSidePerceptor::update() {
  const CameraImage& image = in<CameraImage>();
  out<GoalBoxSidePercept>().side =
      vision::detectGoalBoxSide(in<FieldLines>().lines, image.width, image.height, vision::GoalBoxParams{});
}

NAO_REGISTER_MODULE(GoalBoxSidePerceptor);

}  // namespace nao::modules
