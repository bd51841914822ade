#include "controllers/modules/BehaviorControl.h"

#include "controllers/modules/ModuleField.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

BehaviorControl::BehaviorControl(const ModuleContext& context)
    : params_(context.load<Params>(name())),
      goTo_(params_.goTo),
      look_(std::make_unique<behavior::LookActive>(FieldModel::from(fieldFor(context)), params_.look)) {}

void BehaviorControl::update() {
  const FrameHistory& history = in<FrameHistory>();
  const behavior::BehaviorInput input{history.entries.empty() ? 0.0 : history.entries.back().time,
                                      in<RobotPose>(),
                                      in<BallModel>(),
                                      in<GameState>(),
                                      in<FallState>(),
                                      in<MotionInfo>(),
                                      in<BehaviorCommand>()};
  MotionRequest& motion = out<MotionRequest>();
  if (input.command.goTo) goTo_.run(input, *input.command.goTo, motion);
  else motion = MotionRequest{};  // stand
  look_->run(input, out<HeadMotionRequest>());
}

NAO_REGISTER_MODULE(BehaviorControl);

}  // namespace nao::modules
