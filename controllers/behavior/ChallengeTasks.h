#pragma once
// Option: the Autonomous Calibration Challenge's phase 2 (../shared/reference/calibration-challenge.md):
// five tasks in order, each ended by a report (an arm up and a sentence) and started by the
// referee's head tap after the previous one. A ball task finds the ball of its half
// (FieldBalls), walks to approachDistance from it, stands and looks at it until enough near
// observations are in, and says "The ball is at: x y" (field, mm) from their median. A walk
// task walks to its spot (own goal centre, centre spot, opponent goal centre) facing the
// field, stands, averages its own estimate and steps again while that is more than
// verifyTolerance off, then says "Finished walking". Every walk goes round the balls it knows
// (the rules end the run at a touched ball) and the goal posts, and keeps inside the field.
#include <optional>
#include <string>
#include <vector>

#include "controllers/behavior/BehaviorInput.h"
#include "controllers/behavior/GoToPose.h"
#include "controllers/behavior/StateMachine.h"
#include "perception/FieldDimensions.h"
#include "representations/behavior/HeadMotionRequest.h"
#include "representations/behavior/MotionRequest.h"
#include "representations/infrastructure/ChallengeMode.h"
#include "representations/modeling/FieldBalls.h"

namespace nao::behavior {

class ChallengeTasks {
 public:
  struct Params {
    double settleTime = 1.5;         // s standing after the start before trusting the localization
    double approachDistance = 0.9;   // m from the ball where it is observed ...
    double approachTolerance = 0.15; // m: ... give or take this
    double observeMinTime = 1.0;     // s observing at least ...
    double observeTimeout = 8.0;     // s, then the report takes the best there is
    int observeSamples = 30;         // ... until this many new near observations came in
    double searchLook = 7.0;         // s looking around from the start before walking to search
    double searchReached = 0.3;      // m: the half's centre reached for the search this near
    double searchTurnSpeed = 0.35;   // rad/s turning in place there
    double sweepAmplitude = 1.8;     // rad of head yaw each way while looking around ...
    double sweepPitch = 0.15;        // rad ...
    double sweepSpeed = 0.6;         // rad/s
    double ballClearance = 0.45;     // m: a walk passing a known ball nearer than this goes round it
    double postClearance = 0.4;      // m: ... or a goal post nearer than this (its radius, half a robot's width with arms, walking error)
    double detourClearance = 0.7;    // m: the detour's waypoint from the ball or post
    double waypointReached = 0.25;   // m: a detour waypoint counts as passed this near
    double fieldMargin = 0.3;        // m inside the side lines for waypoints and search poses
    double verifyTime = 1.5;         // s standing on a spot, averaging the estimate
    double verifyTolerance = 0.025;  // m: farther off by the average: step again
    int verifyRounds = 3;            // re-steps at most
    double arrivedDistance = 0.03;   // m: a spot (or the observation pose) reached by the estimate ...
    double arrivedAngle = 0.1;       // rad
    double retargetNear = 0.02;      // m: near the target, re-target on a move of this much
  };
  enum class Task { BallOwn, WalkOwnGoal, WalkCenter, BallOpponent, WalkOpponentGoal };
  enum class State { Localize, FindBall, Search, Approach, Observe, Walk, Verify, Report, WaitForTap, Done };

  struct Output {
    MotionRequest motion;
    HeadMotionRequest head;
    bool lookActive = true;  // the caller's LookActive chooses the head
    std::string report;      // non-empty: start this report now
  };
  // What happened, for the log.
  struct Summary {
    int task = 0;             // the task being done (0..4), 5 when all are done
    int searchPoses = 0, detours = 0, verifySteps = 0;
    std::string lastReport;
  };

  ChallengeTasks(const FieldDimensions& field, const Params& params);
  void restart(double time);
  Output run(const BehaviorInput& in, const ChallengeMode& mode, const FieldBalls& balls);
  // The report is over: wait for the referee's tap.
  void reported(double time);
  State state() const { return machine_.state; }
  Task task() const { return static_cast<Task>(std::min(task_, 4)); }
  bool done() const { return machine_.state == State::Done; }
  const Summary& summary() const { return summary_; }

  // The walk task's spot (field pose, facing the field).
  Pose2 spot(Task task) const;
  // Where to walk next on the way from `from` to `to`: `to` itself, or a waypoint beside a ball
  // the straight way would pass nearer than ballClearance or a goal post it would pass nearer
  // than postClearance (the first such obstacle on the way). Obstacles near one of `passed`
  // (already gone round on this walk) do not count again; `obstacle` gets the one gone round.
  static Eigen::Vector2d detour(const Eigen::Vector2d& from, const Eigen::Vector2d& to, const FieldBalls& balls,
                                const FieldDimensions& field, const Params& params,
                                const std::vector<Eigen::Vector2d>& passed = {}, Eigen::Vector2d* obstacle = nullptr);

 private:
  void startTask(const BehaviorInput& in);
  // Walks towards `target` round the known balls; true once arrived.
  bool walkTo(const BehaviorInput& in, const Pose2& target, const FieldBalls& balls, Output& out);
  static bool isBallTask(Task t) { return t == Task::BallOwn || t == Task::BallOpponent; }

  FieldDimensions field_;
  Params params_;
  StateMachine<State> machine_{State::Localize};
  int task_ = 0;
  GoToPose goTo_;
  std::optional<Eigen::Vector2d> waypoint_;  // the detour being walked to ...
  Eigen::Vector2d waypointObstacle_ = Eigen::Vector2d::Zero();  // ... round this ball or post
  std::vector<Eigen::Vector2d> passed_;      // the balls gone round on this walk
  Pose2 approach_;                           // the observation pose
  Eigen::Vector2d approachBall_ = Eigen::Vector2d::Zero();  // the ball estimate it was planned for
  int observed_ = 0;                         // new observations of the ball while observing
  int searchIndex_ = 0;
  Eigen::Vector3d verifySum_ = Eigen::Vector3d::Zero();
  int verifyImages_ = 0, verifyRound_ = 0;
  double lastPoseTime_ = -1;
  Summary summary_;
};

template <class V>
void describe(V& v, ChallengeTasks::Params& p) {
  v("settleTime", p.settleTime, 0.0, 30.0);
  v("approachDistance", p.approachDistance, 0.5, 3.0);
  v("approachTolerance", p.approachTolerance, 0.01, 1.0);
  v("observeMinTime", p.observeMinTime, 0.0, 30.0);
  v("observeTimeout", p.observeTimeout, 0.1, 60.0);
  v("observeSamples", p.observeSamples, 1, 1000);
  v("searchLook", p.searchLook, 0.1, 60.0);
  v("searchReached", p.searchReached, 0.01, 3.0);
  v("searchTurnSpeed", p.searchTurnSpeed, 0.05, 1.0);
  v("sweepAmplitude", p.sweepAmplitude, 0.1, 2.0);
  v("sweepPitch", p.sweepPitch, -0.6, 0.5);
  v("sweepSpeed", p.sweepSpeed, 0.05, 3.0);
  v("ballClearance", p.ballClearance, 0.0, 3.0);
  v("postClearance", p.postClearance, 0.0, 3.0);
  v("detourClearance", p.detourClearance, 0.0, 3.0);
  v("waypointReached", p.waypointReached, 0.01, 3.0);
  v("fieldMargin", p.fieldMargin, 0.0, 2.0);
  v("verifyTime", p.verifyTime, 0.0, 30.0);
  v("verifyTolerance", p.verifyTolerance, 0.001, 1.0);
  v("verifyRounds", p.verifyRounds, 0, 20);
  v("arrivedDistance", p.arrivedDistance, 0.001, 1.0);
  v("arrivedAngle", p.arrivedAngle, 0.001, 1.0);
  v("retargetNear", p.retargetNear, 0.0, 1.0);
}

// "The ball is at: x y" with x and y in millimetres, as the rules ask.
std::string ballReport(const Eigen::Vector2d& field);

}  // namespace nao::behavior
