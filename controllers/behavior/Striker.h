#pragma once
// Option: a 1vs1 player while the GameController runs the game. INITIAL, SET, FINISHED and
// penalised: stand. READY: walk behind the own half's two balls. PLAYING: of the balls
// it knows (BallTracks; the ball model when it follows one of them), take the nearest one it
// can kick without touching the halfway line (keeping its choice unless another is clearly
// nearer); walk behind it on the line of the chosen kick (KickChoice), round the ball when
// coming from in front of it, and kick. With no such ball known: scan the own half from its
// middle, turning in place (a ball deep in the own half is behind a robot that faces the
// other half). With no ball known at all: search (turn in place). The robot's own field frame:
// it attacks +x.
// player "baseline" is the scripted opponent of `match --opponent baseline`: it walks to the
// ball wherever it lies and kicks it at the opponent goal's centre (no kick choice, no regard
// for the halfway line).
#include <optional>
#include <string>

#include "controllers/behavior/BehaviorInput.h"
#include "controllers/behavior/GoToPose.h"
#include "controllers/behavior/KickChoice.h"
#include "controllers/behavior/StateMachine.h"
#include "perception/FieldDimensions.h"
#include "representations/behavior/MotionRequest.h"
#include "representations/modeling/BallTracks.h"

namespace nao::behavior {

class Striker {
 public:
  struct Params {
    std::string player = "striker";  // or "baseline"
    // Where READY ends: between the own half's two balls (the goal box's corners, placed at
    // SET), behind them, facing the other half: the first kick comes 7 s into PLAYING instead
    // of 17 s from (-1, 0), which had to walk back round a ball (docs/plans/one-vs-one.md).
    Pose2 readyPose{-4.2, 0.0, 0.0};
    double kickBallX = 0.16, kickBallY = 0.05;  // m: the ball in the robot frame at a kick (the kick's own)
    // The ball this near its kick position and the heading this near the kick's direction: the
    // kick starts (the motion engine walks the last centimetres itself, on odometry).
    double alignDistance = 0.25;  // m
    double alignAngle = 0.35;     // rad
    double halfwayClearance = 0.3;   // m: the torso stays this far short of the halfway line
    double searchTurn = 0.5;      // rad/s: turning in place while no ball is known
    double ballLostAfter = 4.0;   // s since the ball was seen: search
    double kickTimeout = 6.0;     // s: a kick not done by then is abandoned ...
    double kickSlack = 0.1;       // m: ... as is one whose ball lies this much farther than alignDistance from the foot
    double scanX = -1.8;          // m: where the robot scans the own half from (y = 0)
    double switchGain = 0.7;      // m: another ball must be this much nearer to change the choice
    double roundBehind = 0.25;    // m: coming from less than this behind the ball (along the kick) ...
    double roundOffset = 0.4;     // m: ... go round it by a point this far behind and beside it
    double rollingShadow = 1.0;   // m: tracks this near a rolling ball are where it was
    double halfwayGuard = 0.05;   // m: the torso this far past the nearest kick pose: ...
    double backOffSpeed = 0.1;    // m/s: ... it steps back (field -x)
    // m: the kick pose (and a way round the ball) stays this far inside the own end line: a ball
    // just in front of the own goal is kicked at an angle rather than from inside the goal
    // (the referee's goal area call).
    double endLineClearance = 0.1;
    GoToPose::Params goTo;
    KickChoiceParams kick;
  };
  enum class State { Stand, Position, Search, Approach, Kick, Wait };

  Striker(const FieldDimensions& field, const Params& params);
  // Fills the motion request from the game state, the pose and the balls.
  void run(const BehaviorInput& in, const BallTracks& balls, MotionRequest& motion);
  void run(const BehaviorInput& in, MotionRequest& motion) { run(in, BallTracks{}, motion); }
  State state() const { return machine_.state; }
  // The chosen ball (robot frame) while the ball model does not follow it: where to look.
  const std::optional<Eigen::Vector2d>& lookAt() const { return lookAt_; }
  const KickChoice& lastChoice() const { return choice_; }
  const std::optional<Eigen::Vector2d>& target() const { return target_; }  // field: the ball chosen
  int kicks() const { return kicks_; }

 private:
  void go(State s, double t);
  void kick(const BehaviorInput& in, MotionRequest& motion) const;  // the current kick's request
  FieldDimensions field_;
  Params params_;
  GoToPose goTo_;
  StateMachine<State> machine_{State::Stand};
  KickChoice choice_;
  int kickId_ = 0, kicks_ = 0;
  std::optional<Eigen::Vector2d> target_;  // field: the ball chosen last
  std::optional<Eigen::Vector2d> lookAt_;
};

const char* strikerStateName(Striker::State s);

template <class V>
void describe(V& v, Striker::Params& p) {
  v("player", p.player, {"striker", "baseline"});
  v("readyX", p.readyPose.x, -10.0, 0.0);
  v("readyY", p.readyPose.y, -10.0, 10.0);
  v("kickBallX", p.kickBallX, 0.0, 0.5);
  v("kickBallY", p.kickBallY, -0.3, 0.3);
  v("alignDistance", p.alignDistance, 0.0, 0.5);
  v("alignAngle", p.alignAngle, 0.0, 1.0);
  v("halfwayClearance", p.halfwayClearance, 0.0, 2.0);
  v("searchTurn", p.searchTurn, 0.0, 2.0);
  v("ballLostAfter", p.ballLostAfter, 0.1, 60.0);
  v("kickTimeout", p.kickTimeout, 0.5, 30.0);
  v("kickSlack", p.kickSlack, 0.0, 2.0);
  v("scanX", p.scanX, -10.0, 0.0);
  v("switchGain", p.switchGain, 0.0, 10.0);
  v("roundBehind", p.roundBehind, 0.0, 2.0);
  v("roundOffset", p.roundOffset, 0.0, 2.0);
  v("rollingShadow", p.rollingShadow, 0.0, 10.0);
  v("halfwayGuard", p.halfwayGuard, 0.0, 1.0);
  v("backOffSpeed", p.backOffSpeed, 0.0, 0.5);
  v("endLineClearance", p.endLineClearance, 0.0, 1.0);
  v("goTo", p.goTo);
  v("kick", p.kick);
}

}  // namespace nao::behavior
