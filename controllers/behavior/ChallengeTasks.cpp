#include "controllers/behavior/ChallengeTasks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace nao::behavior {

namespace {
GoToPose::Params goToParams(const ChallengeTasks::Params& p) {
  GoToPose::Params g;
  g.arrivedDistance = p.arrivedDistance;
  g.arrivedAngle = p.arrivedAngle;
  g.retargetNear = p.retargetNear;
  return g;
}
constexpr double kBallRadius = 0.05;
}  // namespace

std::string ballReport(const Eigen::Vector2d& field) {
  char text[64];
  std::snprintf(text, sizeof text, "The ball is at: %ld %ld", std::lround(field.x() * 1000), std::lround(field.y() * 1000));
  return text;
}

ChallengeTasks::ChallengeTasks(const FieldDimensions& field, const Params& params)
    : field_(field), params_(params), goTo_(goToParams(params)) {}

void ChallengeTasks::restart(double time) {
  machine_.state = State::Done;  // so that go() records the time
  machine_.go(State::Localize, time);
  task_ = 0;
  summary_ = {};
  waypoint_.reset();
  goTo_.restart();
}

void ChallengeTasks::reported(double time) {
  if (machine_.state == State::Report) machine_.go(State::WaitForTap, time);
}

Pose2 ChallengeTasks::spot(Task task) const {
  const double goalX = field_.length / 2;
  switch (task) {
    case Task::WalkOwnGoal: return Pose2(-goalX, 0, 0);
    case Task::WalkOpponentGoal: return Pose2(goalX, 0, M_PI);
    default: return Pose2(0, 0, 0);
  }
}

Eigen::Vector2d ChallengeTasks::detour(const Eigen::Vector2d& from, const Eigen::Vector2d& to, const FieldBalls& balls,
                                       const FieldDimensions& field, const Params& p,
                                       const std::vector<Eigen::Vector2d>& passed, Eigen::Vector2d* obstacle) {
  // The obstacles: the balls it knows (the rules end the run at a touched ball) and the four
  // goal posts, where the field says they stand (a robot that brushes a post falls, and lying
  // against it cannot get up: seed 56 of the challenge rows).
  struct Obstacle {
    Eigen::Vector2d position;
    double clearance;
  };
  std::vector<Obstacle> obstacles;
  for (const FieldBalls::Ball* b : {&balls.own, &balls.opponent})
    if (b->seen) obstacles.push_back({b->position, p.ballClearance});
  const double postY = field.goalInnerWidth / 2 + field.goalPostDiameter / 2;
  for (const double x : {-field.length / 2, field.length / 2})
    for (const double y : {-postY, postY}) obstacles.push_back({Eigen::Vector2d(x, y), p.postClearance});

  const Eigen::Vector2d seg = to - from;
  const double len2 = seg.squaredNorm();
  std::optional<Eigen::Vector2d> first;
  double firstAlong = 2;
  Eigen::Vector2d firstClosest = Eigen::Vector2d::Zero();
  for (const Obstacle& o : obstacles) {
    if (std::any_of(passed.begin(), passed.end(), [&](const Eigen::Vector2d& q) { return (q - o.position).norm() < 0.3; }))
      continue;
    const double along = len2 > 1e-9 ? std::clamp((o.position - from).dot(seg) / len2, 0.0, 1.0) : 0.0;
    const Eigen::Vector2d closest = from + along * seg;
    if ((closest - o.position).norm() >= o.clearance || along >= firstAlong) continue;
    first = o.position;
    firstAlong = along;
    firstClosest = closest;
  }
  if (!first) return to;
  if (obstacle) *obstacle = *first;
  // Beside the obstacle on the side the straight way passes, unless that leaves the field.
  Eigen::Vector2d side = firstClosest - *first;
  if (side.norm() < 1e-6) side = Eigen::Vector2d(-seg.y(), seg.x());
  side.normalize();
  const double maxX = field.length / 2 - p.fieldMargin, maxY = field.width / 2 - p.fieldMargin;
  auto inside = [&](const Eigen::Vector2d& q) { return std::abs(q.x()) <= maxX && std::abs(q.y()) <= maxY; };
  Eigen::Vector2d waypoint = *first + p.detourClearance * side;
  if (!inside(waypoint)) waypoint = *first - p.detourClearance * side;
  waypoint.x() = std::clamp(waypoint.x(), -maxX, maxX);
  waypoint.y() = std::clamp(waypoint.y(), -maxY, maxY);
  return waypoint;
}

bool ChallengeTasks::walkTo(const BehaviorInput& in, const Pose2& target, const FieldBalls& balls, Output& out) {
  const Eigen::Vector2d here(in.pose.pose.x, in.pose.pose.y), there(target.x, target.y);
  if (waypoint_ && (here - *waypoint_).norm() < params_.waypointReached) {
    passed_.push_back(waypointObstacle_);
    waypoint_.reset();
  }
  if (!waypoint_ && in.pose.valid) {
    const Eigen::Vector2d next = detour(here, there, balls, field_, params_, passed_, &waypointObstacle_);
    if ((next - there).norm() > 1e-6) {
      waypoint_ = next;
      ++summary_.detours;
    }
  }
  if (waypoint_) {
    const Eigen::Vector2d d = there - *waypoint_;
    goTo_.run(in, Pose2(waypoint_->x(), waypoint_->y(), std::atan2(d.y(), d.x())), out.motion);
    return false;
  }
  return goTo_.run(in, target, out.motion);
}

void ChallengeTasks::startTask(const BehaviorInput& in) {
  summary_.task = task_;
  waypoint_.reset();
  passed_.clear();
  goTo_.restart();
  verifyRound_ = 0;
  searchIndex_ = 0;
  if (task_ >= 5) {
    machine_.go(State::Done, in.time);
    return;
  }
  machine_.go(isBallTask(task()) ? State::FindBall : State::Walk, in.time);
}

ChallengeTasks::Output ChallengeTasks::run(const BehaviorInput& in, const ChallengeMode& mode, const FieldBalls& balls) {
  Output out;
  const double t = in.time;
  const Eigen::Vector2d here(in.pose.pose.x, in.pose.pose.y);
  const bool ownHalf = task() == Task::BallOwn;
  const FieldBalls::Ball& ball = balls.half(ownHalf);
  auto sweep = [&] {
    out.lookActive = false;
    out.head.mode = HeadMotionRequest::Mode::Sweep;
    out.head.sweepAmplitude = params_.sweepAmplitude;
    out.head.sweepPitch = params_.sweepPitch;
    out.head.sweepSpeed = params_.sweepSpeed;
  };
  auto planApproach = [&] {
    // approachDistance short of the ball on the line from here, facing it.
    Eigen::Vector2d dir = ball.position - here;
    if (dir.norm() < 1e-3) dir = Eigen::Vector2d(ownHalf ? -1 : 1, 0);
    dir.normalize();
    const Eigen::Vector2d p = ball.position - params_.approachDistance * dir;
    approach_ = Pose2(p.x(), p.y(), std::atan2(dir.y(), dir.x()));
    approachBall_ = ball.position;
    goTo_.restart();
    waypoint_.reset();
    passed_.clear();
  };
  switch (machine_.state) {
    case State::Localize:
      if (in.pose.valid && machine_.timeIn(t) >= params_.settleTime) {
        task_ = std::min(mode.headTaps, 5);
        startTask(in);
      }
      break;
    case State::FindBall:
      // Look around from here first: from the start most of the own half is in view.
      if (ball.seen) {
        planApproach();
        machine_.go(State::Approach, t);
      } else if (machine_.timeIn(t) < params_.searchLook) {
        sweep();
      } else {
        machine_.go(State::Search, t);
      }
      break;
    case State::Search: {
      if (ball.seen) {
        planApproach();
        machine_.go(State::Approach, t);
        break;
      }
      // To the half's centre (near is enough), then turning in place there, the head sweeping:
      // from the centre every point of the half is within 3.5 m.
      const Eigen::Vector2d centre((ownHalf ? -1 : 1) * field_.length / 4, 0);
      if (searchIndex_ == 0 && (here - centre).norm() > params_.searchReached) {
        walkTo(in, Pose2(centre.x(), centre.y(), std::atan2(centre.y() - here.y(), centre.x() - here.x())), balls, out);
        break;
      }
      if (searchIndex_ == 0) {
        searchIndex_ = 1;
        ++summary_.searchPoses;
      }
      sweep();
      out.motion = MotionRequest{};
      out.motion.motion = MotionType::Walk;
      out.motion.walkSpeed = Pose2(0, 0, params_.searchTurnSpeed);
      break;
    }
    case State::Approach: {
      if ((ball.position - approachBall_).norm() > 0.15) planApproach();
      // The observation pose needs no precision: standing near it will do.
      const bool near = in.motion.walkToReached && !waypoint_ && machine_.timeIn(t) > 1.0 &&
                        (here - Eigen::Vector2d(approach_.x, approach_.y)).norm() < params_.approachTolerance;
      if (walkTo(in, approach_, balls, out) || near) {
        observed_ = 0;
        lastPoseTime_ = ball.lastSeen;
        machine_.go(State::Observe, t);
      }
      break;
    }
    case State::Observe: {
      out.motion = MotionRequest{};
      out.lookActive = false;
      out.head.mode = HeadMotionRequest::Mode::LookAtFieldPoint;
      out.head.point = Eigen::Vector3d(ball.position.x(), ball.position.y(), kBallRadius);
      out.head.robotPose = Eigen::Vector3d(in.pose.pose.x, in.pose.pose.y, in.pose.pose.theta);
      out.head.camera = CameraId::Bottom;
      if (ball.lastSeen > lastPoseTime_) {
        lastPoseTime_ = ball.lastSeen;
        ++observed_;  // counts the new observations of the ball while standing here
      }
      const bool enough = observed_ >= params_.observeSamples && machine_.timeIn(t) >= params_.observeMinTime;
      if (enough || machine_.timeIn(t) >= params_.observeTimeout) {
        const Eigen::Vector2d p = ball.close > 0 ? ball.closePosition : ball.position;
        out.report = ballReport(p);
        summary_.lastReport = out.report;
        machine_.go(State::Report, t);
      }
      break;
    }
    case State::Walk:
      if (walkTo(in, spot(task()), balls, out)) {
        verifySum_.setZero();
        verifyImages_ = 0;
        lastPoseTime_ = in.pose.time;
        machine_.go(State::Verify, t);
      }
      break;
    case State::Verify: {
      out.motion = MotionRequest{};
      if (in.pose.time > lastPoseTime_) {
        lastPoseTime_ = in.pose.time;
        verifySum_ += Eigen::Vector3d(in.pose.pose.x, in.pose.pose.y, 0);
        ++verifyImages_;
      }
      if (machine_.timeIn(t) < params_.verifyTime) break;
      const Pose2 s = spot(task());
      const Eigen::Vector2d mean = verifyImages_ ? Eigen::Vector2d(verifySum_.head<2>() / verifyImages_) : here;
      if ((mean - Eigen::Vector2d(s.x, s.y)).norm() > params_.verifyTolerance && verifyRound_ < params_.verifyRounds) {
        ++verifyRound_;
        ++summary_.verifySteps;
        goTo_.restart();
        machine_.go(State::Walk, t);
        break;
      }
      out.report = "Finished walking";
      summary_.lastReport = out.report;
      machine_.go(State::Report, t);
      break;
    }
    case State::Report:
      out.motion = MotionRequest{};
      break;
    case State::WaitForTap:
      out.motion = MotionRequest{};
      if (mode.headTaps > task_) {
        task_ = std::min(mode.headTaps, 5);
        startTask(in);
      }
      break;
    case State::Done:
      out.motion = MotionRequest{};
      break;
  }
  return out;
}

}  // namespace nao::behavior
