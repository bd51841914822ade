#pragma once
// Option: a 1vs1 player while the GameController runs the game. INITIAL, SET, FINISHED and
// penalised: stand. READY: walk to the kick-off position in the own half. PLAYING: search the
// ball (turn in place), walk behind it on the line of the chosen kick (KickChoice) and kick;
// while the ball lies in the opponent half (or too near the halfway line to get behind it),
// wait short of the halfway line facing it. The robot's own field frame: it attacks +x.
// player "baseline" is the scripted opponent of `match --opponent baseline`: it walks to the
// ball wherever it lies and kicks it at the opponent goal's centre (no kick choice, no regard
// for the halfway line).
#include <string>

#include "controllers/behavior/BehaviorInput.h"
#include "controllers/behavior/GoToPose.h"
#include "controllers/behavior/KickChoice.h"
#include "controllers/behavior/StateMachine.h"
#include "perception/FieldDimensions.h"
#include "representations/behavior/MotionRequest.h"

namespace nao::behavior {

class Striker {
 public:
  struct Params {
    std::string player = "striker";  // or "baseline"
    Pose2 readyPose{-1.0, 0.0, 0.0};  // where READY ends
    double kickBallX = 0.16, kickBallY = 0.05;  // m: the ball in the robot frame at a kick (the kick's own)
    double alignDistance = 0.05;  // m: the ball this near its kick position ...
    double alignAngle = 0.12;     // rad: ... and the heading this near the kick's direction
    double halfwayClearance = 0.25;  // m: the torso stays this far short of the halfway line
    double waitX = -0.8;          // m: where the robot waits while the ball is out of its reach
    double searchTurn = 0.5;      // rad/s: turning in place while no ball is known
    double ballLostAfter = 4.0;   // s since the ball was seen: search
    double kickTimeout = 4.0;     // s: a kick not done by then is abandoned
    GoToPose::Params goTo;
    KickChoiceParams kick;
  };
  enum class State { Stand, Position, Search, Approach, Kick, Wait };

  Striker(const FieldDimensions& field, const Params& params);
  // Fills the motion request from the game state, the pose and the ball.
  void run(const BehaviorInput& in, MotionRequest& motion);
  State state() const { return machine_.state; }
  const KickChoice& lastChoice() const { return choice_; }
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
  v("waitX", p.waitX, -5.0, 0.0);
  v("searchTurn", p.searchTurn, 0.0, 2.0);
  v("ballLostAfter", p.ballLostAfter, 0.1, 60.0);
  v("kickTimeout", p.kickTimeout, 0.5, 30.0);
  v("goTo", p.goTo);
  v("kick", p.kick);
}

}  // namespace nao::behavior
