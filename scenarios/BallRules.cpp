#include "scenarios/BallRules.h"

#include <algorithm>
#include <cmath>

namespace nao::sim {

BallRules::BallRules(const FieldDimensions& field) : BallRules(field, Params{}) {}

BallRules::BallRules(const FieldDimensions& field, const Params& params) : field_(field), params_(params) {}

double BallRules::attackSign(int team) const {
  // Home attacks +x while it defends the goal at negative x.
  const double home = homeNegative_ ? 1.0 : -1.0;
  return team == 0 ? home : -home;
}

std::vector<Eigen::Vector2d> BallRules::startPoints() const {
  const double x = field_.length / 2 - field_.goalBoxAreaLength, y = field_.goalBoxAreaWidth / 2;
  return {{-x, -y}, {-x, y}, {x, -y}, {x, y}};
}

void BallRules::replaced(int ball) {
  if (ball >= 0 && ball < static_cast<int>(states_.size())) states_[static_cast<std::size_t>(ball)] = State{};
}

std::vector<BallRules::Call> BallRules::update(double t, const std::vector<Ball>& balls,
                                               const std::vector<Touch>& touches,
                                               const std::vector<Eigen::Vector2d>& robots) {
  std::vector<Call> calls;
  if (states_.size() < balls.size()) states_.resize(balls.size());
  // A line belongs to its region: the ball is beyond a boundary line only when no part of it
  // touches the line; it is in a half only beyond the halfway line's edge.
  const double outX = field_.length / 2 + field_.lineWidth / 2 + params_.ballRadius;
  const double outY = field_.width / 2 + field_.lineWidth / 2 + params_.ballRadius;
  const double halfway = field_.lineWidth / 2;
  for (std::size_t i = 0; i < balls.size(); ++i) {
    State& s = states_[i];
    const Ball& b = balls[i];
    if (s.outOfPlay || !b.inPlay) continue;
    for (const Touch& touch : touches) {
      if (touch.ball != static_cast<int>(i)) continue;
      if (touch.team == s.cancelled) s.cancelled = -1;
      if (s.attacker >= 0 && touch.team != s.attacker) {
        // The defender played it: after it crossed, the attacker's point is gone.
        if (s.crossed) s.cancelled = s.attacker;
        s.attacker = -1;
        s.crossed = false;
      }
      if (b.position.x() * attackSign(touch.team) < 0) {  // a kick from the own half
        s.attacker = touch.team;
        s.crossed = false;
        s.slowSince = -1;
        s.stoppedJudged = false;
      }
    }
    if (s.attacker >= 0 && b.position.x() * attackSign(s.attacker) > halfway) s.crossed = true;

    const int end = b.position.x() >= 0 ? 1 : -1, side = b.position.y() >= 0 ? 1 : -1;
    Call call;
    call.t = t;
    call.ball = static_cast<int>(i);
    call.at = b.position;
    if (std::abs(b.position.x()) > outX && std::abs(b.position.y()) < field_.goalInnerWidth / 2) {
      // A goal: for the team attacking that goal, whoever touched the ball last.
      call.kind = "point";
      call.how = "goal";
      call.team = attackSign(0) == end ? 0 : 1;
      // The ball goes back to the scorer: the start point in the scorer's half farthest from it.
      const Eigen::Vector2d scorer = call.team < static_cast<int>(robots.size()) ? robots[static_cast<std::size_t>(call.team)]
                                                                                 : Eigen::Vector2d::Zero();
      double best = -1;
      for (const Eigen::Vector2d& p : startPoints())
        if (p.x() * attackSign(call.team) < 0 && (p - scorer).norm() > best) {
          best = (p - scorer).norm();
          call.replaceAt = p;
        }
    } else if (std::abs(b.position.y()) > outY) {
      call.kind = "ball_out_side";
      call.replaceAt = Eigen::Vector2d(std::clamp(b.position.x(), -field_.length / 2, field_.length / 2), side * field_.width / 2);
    } else if (std::abs(b.position.x()) > outX) {
      call.kind = "ball_out_end";
      call.replaceAt = Eigen::Vector2d(end * (field_.length / 2 - field_.goalBoxAreaLength), side * field_.goalBoxAreaWidth / 2);
    }
    if (!call.kind.empty()) {
      s.outOfPlay = true;
      calls.push_back(call);
      continue;
    }

    if (b.velocity.norm() >= params_.stopSpeed) {
      s.slowSince = -1;
      s.stoppedJudged = false;
      continue;
    }
    if (s.slowSince < 0) s.slowSince = t;
    if (s.stoppedJudged || t - s.slowSince < params_.stopTime - 1e-9) continue;
    s.stoppedJudged = true;
    if (s.attacker >= 0 && s.crossed && b.position.x() * attackSign(s.attacker) > halfway) {
      call.team = s.attacker;
      call.kind = "point";
      call.how = "ball_in_half";
      calls.push_back(call);
    } else if (s.cancelled >= 0 && b.position.x() * attackSign(s.cancelled) > halfway) {
      call.team = s.cancelled;
      call.kind = "no_point";
      call.how = "intercepted";
      calls.push_back(call);
    }
    // Judged (or rolled back): the next point needs a new kick from the own half.
    s.attacker = s.cancelled = -1;
    s.crossed = false;
  }
  return calls;
}

}  // namespace nao::sim
