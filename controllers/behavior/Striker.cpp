#include "controllers/behavior/Striker.h"

#include <algorithm>
#include <cmath>

namespace nao::behavior {

const char* strikerStateName(Striker::State s) {
  switch (s) {
    case Striker::State::Stand: return "stand";
    case Striker::State::Position: return "position";
    case Striker::State::Search: return "search";
    case Striker::State::Approach: return "approach";
    case Striker::State::Kick: return "kick";
    case Striker::State::Wait: return "wait";
  }
  return "?";
}

Striker::Striker(const FieldDimensions& field, const Params& params)
    : field_(field), params_(params), goTo_(params.goTo) {}

void Striker::go(State s, double t) {
  if (s != machine_.state && (s == State::Position || s == State::Approach || s == State::Wait)) goTo_.restart();
  machine_.go(s, t);
}

void Striker::kick(const BehaviorInput& in, MotionRequest& motion) const {
  motion.motion = MotionType::Kick;
  motion.kickId = kickId_;
  motion.kickDirection = Pose2::wrap(choice_.direction - in.pose.pose.theta);
  motion.ballPosition = in.ball.position;
}

void Striker::run(const BehaviorInput& in, MotionRequest& motion) {
  const double t = in.time;
  motion = MotionRequest{};  // stand unless a state says otherwise
  const gc::State game = in.game.state;
  if (!in.game.fromGameController || in.game.penalised() ||
      (game != gc::State::Ready && game != gc::State::Playing)) {
    go(State::Stand, t);
    return;
  }
  if (game == gc::State::Ready) {
    go(State::Position, t);
    goTo_.run(in, params_.readyPose, motion);
    return;
  }
  // A kick under way runs to its end (or its time-out).
  if (machine_.state == State::Kick) {
    if (!in.motion.kickDone && machine_.timeIn(t) < params_.kickTimeout) {
      kick(in, motion);
      return;
    }
    go(State::Search, t);
  }
  const bool ballKnown = in.ball.valid && !in.ball.lost && in.ball.fieldValid && t - in.ball.seenTime < params_.ballLostAfter;
  if (!in.pose.valid || !ballKnown) {
    go(State::Search, t);
    motion.motion = MotionType::Walk;
    motion.walkSpeed = Pose2(0, 0, params_.searchTurn);
    return;
  }
  const Eigen::Vector2d ball = in.ball.rolling ? in.ball.fieldEndPosition : in.ball.fieldPosition;
  const bool baseline = params_.player == "baseline";
  if (baseline) {
    const Eigen::Vector2d goal(field_.length / 2, 0);
    choice_ = KickChoice{KickChoice::Kind::Goal, std::atan2(goal.y() - ball.y(), goal.x() - ball.x()), goal, 0};
  } else {
    choice_ = chooseKick(ball, std::nullopt, field_, params_.kick);
  }
  // The kick pose: the ball at the kick's position in front of the foot, facing the direction.
  const double c = std::cos(choice_.direction), s = std::sin(choice_.direction);
  const Eigen::Vector2d at = ball - Eigen::Vector2d(c * params_.kickBallX - s * params_.kickBallY,
                                                    s * params_.kickBallX + c * params_.kickBallY);
  const double limitX = -field_.lineWidth / 2 - params_.halfwayClearance;
  if (!baseline && at.x() > limitX) {
    // Out of reach: the robot would touch the halfway line. Wait facing the ball.
    go(State::Wait, t);
    const Eigen::Vector2d wait(params_.waitX, std::clamp(ball.y(), -field_.width / 2 + 0.5, field_.width / 2 - 0.5));
    const Eigen::Vector2d to = ball - wait;
    goTo_.run(in, Pose2(wait.x(), wait.y(), std::atan2(to.y(), to.x())), motion);
    return;
  }
  // Aligned: the ball where the kick wants it and the heading along the kick.
  const Eigen::Vector2d error = in.ball.position - Eigen::Vector2d(params_.kickBallX, params_.kickBallY);
  const double headingError = std::abs(Pose2::wrap(choice_.direction - in.pose.pose.theta));
  if (!in.ball.rolling && error.norm() < params_.alignDistance && headingError < params_.alignAngle) {
    go(State::Kick, t);
    ++kickId_;
    ++kicks_;
    kick(in, motion);
    return;
  }
  go(State::Approach, t);
  goTo_.run(in, Pose2(at.x(), at.y(), choice_.direction), motion);
}

}  // namespace nao::behavior
