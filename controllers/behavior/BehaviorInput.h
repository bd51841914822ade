#pragma once
// What every behaviour option reads: the cognition cycle's models and the motion side's state.
#include "representations/behavior/BehaviorCommand.h"
#include "representations/infrastructure/GameState.h"
#include "representations/modeling/BallModel.h"
#include "representations/modeling/RobotPose.h"
#include "representations/motion/MotionInfo.h"
#include "representations/perception/FallState.h"

namespace nao::behavior {

struct BehaviorInput {
  double time = 0;  // s, backend clock: the newest motion cycle's
  const RobotPose& pose;
  const BallModel& ball;
  const GameState& game;
  const FallState& fall;
  const MotionInfo& motion;
  const BehaviorCommand& command;
};

}  // namespace nao::behavior
