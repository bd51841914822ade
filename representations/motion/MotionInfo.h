#pragma once
// What the motion engine does now (MotionEngine provides it).
#include "representations/behavior/MotionRequest.h"
#include "robot/math/Pose2.h"

namespace nao {

struct MotionInfo {
  MotionType motion = MotionType::Stand;  // the motion now executed
  bool stable = true;          // standing or walking on its feet, nothing in transition
  bool walkToReached = false;  // WalkTo: the target is reached and the robot stands
  bool kickDone = false;       // Kick: the kick with the current kickId is over
  bool upright = true;         // not fallen (after a get-up: true again)
  int getUpAttempts = 0;
  bool armRaised = false;      // the requested arm is up (its measured joints near the raised pose)
  Pose2 walkSpeed;             // the speed the walk applies now (after its limits and ramps)
};

}  // namespace nao
