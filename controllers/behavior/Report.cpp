#include "controllers/behavior/Report.h"

namespace nao::behavior {

void Report::start(const std::string& text, double time) {
  text_ = text;
  machine_.state = State::Idle;  // a running report restarts
  machine_.go(State::Raising, time);
}

bool Report::run(const BehaviorInput& in, ArmMotionRequest& arm, SpeechRequest& speech) {
  const auto side = params_.leftArm ? ArmMotionRequest::Arm::Left : ArmMotionRequest::Arm::Right;
  switch (machine_.state) {
    case State::Idle:
    case State::Done:
      arm.raise = ArmMotionRequest::Arm::None;
      return machine_.state == State::Done;
    case State::Raising:
      arm.raise = side;
      if (in.motion.armRaised || machine_.timeIn(in.time) >= params_.armTimeout) {
        say(speech, text_);
        machine_.go(State::Holding, in.time);
      }
      return false;
    case State::Holding:
      arm.raise = side;
      if (machine_.timeIn(in.time) < params_.holdTime) return false;
      machine_.go(State::Done, in.time);
      arm.raise = ArmMotionRequest::Arm::None;
      return true;
  }
  return false;
}

}  // namespace nao::behavior
