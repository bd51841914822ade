#pragma once
// The 2021 1vs1 challenge's rules on robots (../shared/reference/referee-and-match.md,
// "Penalties"), judged from the simulator's truth once per robot cycle for one robot: leaving
// the carpet of the own half, touching or crossing the halfway line, more than 5 s inside a
// goal, fallen (no get-up started within 5 s, or not standing within 20 s and upright for
// 10 s), inactive for 10 s, a stance wider than the shoulders for more than 5 s, a hand on the
// ball (not while fallen), and in SET: not inside the own half when SET starts, moving the legs
// (once the robot has had time to hear SET).
// The match measures what a rule needs (RobotRules::Truth) and applies the calls.
#include <array>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "perception/FieldDimensions.h"
#include "robot/nao/GameController.h"
#include "scenarios/GameControllerSim.h"

namespace nao::sim {

class RobotRules {
 public:
  struct Params {
    double fallTilt = 50, fallHeight = 0.15;  // deg, m: fallen beyond either
    // deg, m: standing within both. The torso stands 0.227 m high and walks at 0.222, a few mm
    // lower on a randomised robot (0.22 here called robots that stood, tilted 4 deg, fallen);
    // kneeling upright it is about 0.19.
    double upTilt = 20, upHeight = 0.20;
    double getUpStart = 5;    // s from a fall to the start of a get-up
    double getUpLimit = 20;   // s from a fall to standing
    double uprightTime = 10;  // s standing that end a fall
    double getUpProgress = 15;  // deg of tilt (or 0.05 m of height) regained: a get-up started
    double inactiveTime = 10;
    double stanceWidth = 0.30;  // m between the feet's centres: wider than the shoulders
    double stanceTime = 5;
    double goalTime = 5;
    double setMotion = 0.05;  // m a foot may move in SET (settling, not walking)
    // s after SET began before the feet must keep still: the robot hears SET from the next
    // GameController packet (every 0.5 s) and finishes the step it is in (up to 0.5 s). At
    // 0 s a robot was called 0.08 s into SET, before its packet came (eval match seed 5).
    double setGrace = 1.0;
  };
  struct Truth {
    std::array<Eigen::Vector2d, 8> soleCorners;  // field frame (both soles)
    std::array<Eigen::Vector2d, 2> feet;         // the soles' centres
    Eigen::Vector2d torso{0, 0};                 // field frame
    double tilt = 0;        // deg: the torso's angle from upright
    double height = 0.3;    // m: the torso's height
    bool active = true;     // walking or turning, or the head searching or aimed at a ball
    bool handOnBall = false;
  };
  struct Call {
    PenaltyRule rule;
    std::string evidence;
  };

  RobotRules(const FieldDimensions& field, int team);
  RobotRules(const FieldDimensions& field, int team, const Params& params);
  void setHomeDefendsNegativeX(bool negative) { homeNegative_ = negative; }

  // Judges one cycle at `t` in GameController state `state`; returns the call or nothing.
  // A robot that is penalised is not judged (call removed() and placed() around the removal).
  std::optional<Call> update(double t, gc::State state, const Truth& truth);
  // The robot was taken out or placed (standing) by the referee: every timer starts again.
  void placed();
  bool fallen() const { return fallenSince_ >= 0; }

 private:
  double ownSign() const;  // the x sign of the own half
  FieldDimensions field_;
  int team_;
  Params params_;
  bool homeNegative_ = true;
  gc::State lastState_ = gc::State::Initial;
  double fallenSince_ = -1, worstTilt_ = 0, lowest_ = 1, standingSince_ = -1;
  bool getUpStarted_ = false;
  double inactiveSince_ = -1, wideSince_ = -1, inGoalSince_ = -1;
  std::array<Eigen::Vector2d, 2> setFeet_;
  double setSince_ = 0;
  bool setFeetTaken_ = false, setJudged_ = false;
};

}  // namespace nao::sim
