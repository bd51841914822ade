#pragma once
// The 2021 1vs1 challenge's ball rules (../shared/reference/referee-and-match.md, "Points",
// "Ball out of the field"), judged from the simulator's truth once per robot cycle: a ball
// kicked from the own half that stops inside the field in the opponent half is a point, unless
// the defender touched it after it crossed the halfway line; a goal is a point for the team
// attacking that goal (own goals count for the other side) and the ball goes back to the
// scorer; a ball over a side line goes back onto that line where it left, over an end line
// (not a goal) onto the goal box corner on that side. The match applies the replacements and
// says so (replaced()).
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "perception/FieldDimensions.h"

namespace nao::sim {

class BallRules {
 public:
  struct Params {
    double ballRadius = 0.05;  // m
    double stopSpeed = 0.02;   // m/s: slower than this ...
    double stopTime = 0.5;     // s: ... for this long is a stopped ball
  };
  struct Ball {
    Eigen::Vector2d position{0, 0}, velocity{0, 0};  // m, m/s, field frame (truth)
    bool inPlay = true;  // false: off the field (not yet placed); not judged
  };
  struct Touch {
    int ball = 0;
    int team = 0;  // 0 home, 1 away
  };
  // A call: kind "point" (how "goal" or "ball_in_half"), "no_point" (how "intercepted"),
  // "ball_out_side", "ball_out_end"; `at` where the ball was; `replaceAt` where it goes.
  struct Call {
    double t = 0;
    std::string kind, how;
    int team = -1, ball = 0;
    Eigen::Vector2d at{0, 0};
    std::optional<Eigen::Vector2d> replaceAt;
  };

  explicit BallRules(const FieldDimensions& field);
  BallRules(const FieldDimensions& field, const Params& params);

  // Which goal the home team defends: negative x in the first half, positive after the switch.
  void setHomeDefendsNegativeX(bool negative) { homeNegative_ = negative; }
  // Judges the balls as they are at `t` with the touches since the last call (the world's
  // latched robot-ball contacts) and the robots' positions (home, away; for the ball returned
  // after a goal). A ball with a replacement is out of play until replaced().
  std::vector<Call> update(double t, const std::vector<Ball>& balls, const std::vector<Touch>& touches,
                           const std::vector<Eigen::Vector2d>& robots);
  // The match put ball `ball` where the call said (or anywhere, e.g. at a kick-off): its
  // history starts again.
  void replaced(int ball);

  // The four ball start points: the goal box corners inside the field (goal free-kick positions).
  std::vector<Eigen::Vector2d> startPoints() const;
  // +1 or -1: the x direction of `team`'s opponent half.
  double attackSign(int team) const;

 private:
  struct State {
    int attacker = -1;       // the team whose kick from its own half the ball is on
    bool crossed = false;    // it has crossed the halfway line into the attacker's opponent half
    int cancelled = -1;      // the team whose point the defender's touch after the crossing cancelled
    double slowSince = -1;
    bool stoppedJudged = false;  // this stop was judged already
    bool outOfPlay = false;      // waiting for replaced()
  };
  FieldDimensions field_;
  Params params_;
  bool homeNegative_ = true;
  std::vector<State> states_;
};

}  // namespace nao::sim
