#pragma once
// Option: walk to a field pose by the self-localization. The target goes to the walk in the
// odometry frame (as the localization's estimate maps it: RobotPose::odometry), so the walk
// closes the loop on odometry between images and the estimate corrects it; the target is sent
// again only when the estimate moves it by more than the re-target distance (the estimate's
// jitter must not keep the robot stepping). The walk stops within its own tolerance of the
// odometry target; when it stands there while the estimate still says "not arrived", the target
// goes out again after nudgeAfter (a fresh id: the walk steps once more). Until the pose is
// valid the robot stands, and turns in place once it has been lost for lostTurnAfter.
#include "controllers/behavior/BehaviorInput.h"
#include "controllers/behavior/StateMachine.h"
#include "representations/behavior/MotionRequest.h"

namespace nao::behavior {

class GoToPose {
 public:
  struct Params {
    double retargetFar = 0.15;        // m: re-target when the estimate moves the target this much ...
    double retargetNear = 0.03;       // m: ... or this much within nearDistance of it
    double retargetAngle = 0.05;      // rad
    double nearDistance = 0.5;        // m
    double arrivedDistance = 0.05;    // m: arrived by the estimate ...
    double arrivedAngle = 0.06;       // rad
    double nudgeAfter = 1.0;          // s the walk has stood at its target while the estimate says not arrived: send it again
    // Lost this long (the pose not valid), the robot turns in place at lostTurnSpeed while the
    // head sweeps: standing, it sees the same features that did not settle the estimate, for as
    // long as it stands (a challenge robot stood lost for 500 s). 0: it stands.
    double lostTurnAfter = 6.0;       // s
    double lostTurnSpeed = 0.4;       // rad/s
  };
  enum class State { WaitForPose, Walk, Arrived };

  GoToPose() = default;
  explicit GoToPose(const Params& params) : params_(params) {}
  // Fills the motion request; returns true once arrived (by the estimate).
  bool run(const BehaviorInput& in, const Pose2& target, MotionRequest& request);
  // A new walk: the next run sends its target afresh. The target ids keep counting (the motion
  // engine takes a target when its id changes).
  void restart() {
    machine_.state = State::WaitForPose;
    haveTarget_ = false;
    reachedSince_ = -1;
  }
  State state() const { return machine_.state; }

 private:
  Params params_;
  StateMachine<State> machine_{State::WaitForPose};
  bool haveTarget_ = false;
  Pose2 odometryTarget_;
  int targetId_ = 0;
  double reachedSince_ = -1;  // s: since when the walk reports its target reached (-1: it does not)
  double lostSince_ = -1;     // s: since when the pose is not valid (-1: it is)
};

template <class V>
void describe(V& v, GoToPose::Params& p) {
  v("retargetFar", p.retargetFar, 0.0, 5.0);
  v("retargetNear", p.retargetNear, 0.0, 1.0);
  v("retargetAngle", p.retargetAngle, 0.0, 1.0);
  v("nearDistance", p.nearDistance, 0.0, 10.0);
  v("arrivedDistance", p.arrivedDistance, 0.0, 1.0);
  v("arrivedAngle", p.arrivedAngle, 0.0, 1.0);
  v("nudgeAfter", p.nudgeAfter, 0.1, 60.0);
  v("lostTurnAfter", p.lostTurnAfter, 0.0, 600.0);
  v("lostTurnSpeed", p.lostTurnSpeed, 0.0, 1.5);
}

}  // namespace nao::behavior
