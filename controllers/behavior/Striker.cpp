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

void Striker::run(const BehaviorInput& in, const BallTracks& balls, MotionRequest& motion) {
  const double t = in.time;
  motion = MotionRequest{};  // stand unless a state says otherwise
  lookAt_.reset();
  const gc::State game = in.game.state;
  if (!in.game.fromGameController || in.game.penalised() ||
      (game != gc::State::Ready && game != gc::State::Playing)) {
    go(State::Stand, t);
    target_.reset();
    return;
  }
  if (game == gc::State::Ready) {
    go(State::Position, t);
    target_.reset();
    goTo_.run(in, params_.readyPose, motion);
    return;
  }
  // A kick under way runs to its end (or its time-out), unless the ball went off before the
  // foot reached it (pushed while the motion engine walked the last centimetres): following it
  // there would walk the robot after it, to the halfway line.
  const bool overshot = in.pose.valid && params_.player != "baseline" &&
                        in.pose.pose.x > -field_.lineWidth / 2 - params_.halfwayClearance + params_.halfwayGuard;
  if (machine_.state == State::Kick) {
    // The ball still in front of the foot, and (nudged while the engine walked) not now so near
    // the halfway line that the kicking foot would touch it.
    const bool ballStays =
        !in.ball.rolling &&
        (in.ball.position - Eigen::Vector2d(params_.kickBallX, params_.kickBallY)).norm() <
            params_.alignDistance + params_.kickSlack &&
        (params_.player == "baseline" || !in.ball.fieldValid ||
         in.ball.fieldPosition.x() - params_.kickBallX <= -field_.lineWidth / 2 - params_.halfwayClearance);
    if (!in.motion.kickDone && machine_.timeIn(t) < params_.kickTimeout && ballStays && !overshot) {
      kick(in, motion);
      return;
    }
    go(State::Search, t);
    target_.reset();
  }
  const bool modelKnown = in.ball.valid && !in.ball.lost && in.ball.fieldValid && t - in.ball.seenTime < params_.ballLostAfter;
  const Eigen::Vector2d modelBall = in.ball.rolling ? in.ball.fieldEndPosition : in.ball.fieldPosition;
  const bool baseline = params_.player == "baseline";
  auto search = [&] {
    go(State::Search, t);
    motion.motion = MotionType::Walk;
    motion.walkSpeed = Pose2(0, 0, params_.searchTurn);
  };
  if (!in.pose.valid) return search();
  const Eigen::Vector2d robot(in.pose.pose.x, in.pose.pose.y);
  // Past the nearest kick pose to the halfway line (a walk that overshot): step back first.
  if (overshot) {
    go(State::Wait, t);
    motion.motion = MotionType::Walk;
    motion.walkSpeed = Pose2(-params_.backOffSpeed * std::cos(in.pose.pose.theta), params_.backOffSpeed * std::sin(in.pose.pose.theta), 0);
    return;
  }
  // The kick pose for a ball: the ball at the kick's position in front of the foot, facing the
  // kick's direction. Reachable: the robot's torso stays short of the halfway line there.
  const double limitX = -field_.lineWidth / 2 - params_.halfwayClearance;
  auto kickPose = [&](const Eigen::Vector2d& ball, double direction) {
    const double c = std::cos(direction), s = std::sin(direction);
    return Eigen::Vector2d(ball - Eigen::Vector2d(c * params_.kickBallX - s * params_.kickBallY,
                                                  s * params_.kickBallX + c * params_.kickBallY));
  };
  auto reachable = [&](const Eigen::Vector2d& ball) {
    const bool inPlay = std::abs(ball.x()) <= field_.length / 2 && std::abs(ball.y()) <= field_.width / 2 + 0.1;
    return inPlay && (baseline || kickPose(ball, 0).x() <= limitX);
  };

  // Which ball: the nearest reachable one known, the last choice kept unless another is
  // clearly nearer. The ball model's ball is one of them while it is known.
  std::optional<Eigen::Vector2d> best;
  double bestCost = 1e9;
  auto consider = [&](const Eigen::Vector2d& ball) {
    if (!reachable(ball)) return;
    double cost = (ball - robot).norm();
    if (target_ && (ball - *target_).norm() < 0.5) cost -= params_.switchGain;
    if (cost < bestCost) bestCost = cost, best = ball;
  };
  if (modelKnown) consider(modelBall);
  // A rolling ball leaves a track behind where it was seen last: not a ball to go for.
  const bool modelRolls = modelKnown && in.ball.rolling;
  if (!baseline)
    for (const auto& track : balls.tracks)
      if (!modelRolls || (track.position - in.ball.fieldPosition).norm() > params_.rollingShadow) consider(track.position);
  if (!best) {
    target_.reset();
    if (!modelKnown && balls.tracks.empty()) return search();
    // Known balls, none to kick: scan the own half from its middle, turning there.
    go(State::Wait, t);
    const Eigen::Vector2d scan(params_.scanX, 0);
    if ((robot - scan).norm() > 0.3) {
      goTo_.run(in, Pose2(scan.x(), scan.y(), std::atan2(-robot.y(), scan.x() - robot.x())), motion);
    } else {
      motion.motion = MotionType::Walk;
      motion.walkSpeed = Pose2(0, 0, params_.searchTurn);
    }
    return;
  }
  target_ = best;
  // Near the model's ball: its estimate (relative, through odometry between images) is the
  // better one; else the track's through the pose.
  const bool onModel = modelKnown && (modelBall - *best).norm() < 0.5;
  const Eigen::Vector2d ball = onModel ? modelBall : *best;
  const Eigen::Vector2d ballRelative = onModel ? in.ball.position : Eigen::Vector2d(in.pose.pose.inverse() * ball);
  if (!onModel) lookAt_ = ballRelative;
  if (baseline) {
    const Eigen::Vector2d goal(field_.length / 2, 0);
    choice_ = KickChoice{KickChoice::Kind::Goal, std::atan2(goal.y() - ball.y(), goal.x() - ball.x()), goal, 0};
  } else {
    choice_ = chooseKick(ball, std::nullopt, field_, params_.kick);
  }
  const Eigen::Vector2d at = kickPose(ball, choice_.direction);
  if (!baseline && at.x() > limitX) {
    // This kick's pose would touch the halfway line: the straight one (reachable) instead.
    choice_ = KickChoice{KickChoice::Kind::Advance, 0.0, ball + Eigen::Vector2d(params_.kick.travel, 0), 0};
  }
  // A ball just in front of the own end line has no kick pose behind it on the field: the
  // smallest turn of the kick (towards the field's middle first) whose pose is on it, else the
  // turn whose pose is furthest from the line.
  const double minX = -field_.length / 2 + params_.endLineClearance;
  if (!baseline && kickPose(ball, choice_.direction).x() < minX) {
    constexpr double kStep = 5 * M_PI / 180;
    const double towardsMiddle = ball.y() > 0 ? -1 : 1;
    double turned = choice_.direction, turnedX = kickPose(ball, turned).x();
    for (double turn = kStep; turn <= M_PI / 2 + 1e-9 && turnedX < minX; turn += kStep)
      for (double sign : {towardsMiddle, -towardsMiddle}) {
        const double direction = Pose2::wrap(choice_.direction + sign * turn);
        const double x = kickPose(ball, direction).x();
        if (x > turnedX + 1e-9) turned = direction, turnedX = x;
        if (turnedX >= minX) break;
      }
    choice_ = KickChoice{KickChoice::Kind::Advance, turned,
                         ball + params_.kick.travel * Eigen::Vector2d(std::cos(turned), std::sin(turned)), 0};
  }
  const Eigen::Vector2d kickAt = kickPose(ball, choice_.direction);
  // Aligned: the ball where the kick wants it and the heading along the kick.
  const Eigen::Vector2d error = ballRelative - Eigen::Vector2d(params_.kickBallX, params_.kickBallY);
  const double headingError = std::abs(Pose2::wrap(choice_.direction - in.pose.pose.theta));
  if (onModel && !in.ball.rolling && error.norm() < params_.alignDistance && headingError < params_.alignAngle) {
    go(State::Kick, t);
    ++kickId_;
    ++kicks_;
    kick(in, motion);
    return;
  }
  go(State::Approach, t);
  // Coming from in front of or beside the ball: round it by a point behind it on the robot's side.
  const double c = std::cos(choice_.direction), s = std::sin(choice_.direction);
  const Eigen::Vector2d fromBall = robot - ball;
  const double along = c * fromBall.x() + s * fromBall.y(), across = -s * fromBall.x() + c * fromBall.y();
  if (!baseline && along > -params_.roundBehind) {
    const double side = across >= 0 ? 1 : -1;
    Eigen::Vector2d via = ball + Eigen::Vector2d(-c * params_.roundOffset - s * side * params_.roundOffset,
                                                 -s * params_.roundOffset + c * side * params_.roundOffset);
    via.x() = std::clamp(via.x(), minX, limitX);
    goTo_.run(in, Pose2(via.x(), via.y(), choice_.direction), motion);
    return;
  }
  goTo_.run(in, Pose2(kickAt.x(), kickAt.y(), choice_.direction), motion);
}

}  // namespace nao::behavior
