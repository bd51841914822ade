#include "scenarios/RobotRules.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace nao::sim {

namespace {

std::string format(const char* fmt, double a, double b = 0, double c = 0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, fmt, a, b, c);
  return buf;
}

}  // namespace

RobotRules::RobotRules(const FieldDimensions& field, int team) : RobotRules(field, team, Params{}) {}

RobotRules::RobotRules(const FieldDimensions& field, int team, const Params& params)
    : field_(field), team_(team), params_(params) {}

// +1 or -1: x times this is how far a point lies inside the own half.
double RobotRules::ownSign() const {
  const double homeOwn = homeNegative_ ? -1.0 : 1.0;
  return team_ == 0 ? homeOwn : -homeOwn;
}

void RobotRules::placed() {
  fallenSince_ = standingSince_ = inactiveSince_ = wideSince_ = inGoalSince_ = -1;
  getUpStarted_ = false;
}

std::optional<RobotRules::Call> RobotRules::update(double t, gc::State state, const Truth& truth) {
  const double own = ownSign();
  const double halfwayEdge = field_.lineWidth / 2;
  const gc::State before = lastState_;
  lastState_ = state;

  if (state == gc::State::Set) {
    if (before != gc::State::Set) {
      setSince_ = t;
      setFeetTaken_ = false;
      setJudged_ = false;
      // Inside the own half: every sole corner short of the halfway line and within the lines
      // (a line belongs to its region; the halfway line to neither half, a goal's inside neither).
      for (const Eigen::Vector2d& c : truth.soleCorners) {
        const bool inside = c.x() * own > halfwayEdge && std::abs(c.x()) <= field_.length / 2 + halfwayEdge &&
                            std::abs(c.y()) <= field_.width / 2 + halfwayEdge;
        if (!inside) {
          setJudged_ = true;
          return Call{PenaltyRule::IllegalPositionInSet,
                      format("a sole corner at (%.2f, %.2f) m when SET began", c.x(), c.y())};
        }
      }
    }
    if (t - setSince_ < params_.setGrace) return std::nullopt;
    if (!setFeetTaken_) {
      setFeet_ = truth.feet;
      setFeetTaken_ = true;
    }
    for (int f = 0; f < 2 && !setJudged_; ++f) {
      const double moved = (truth.feet[static_cast<std::size_t>(f)] - setFeet_[static_cast<std::size_t>(f)]).norm();
      if (moved > params_.setMotion) {
        setJudged_ = true;
        return Call{PenaltyRule::MotionInSet, format("a foot moved %.3f m in SET", moved)};
      }
    }
    return std::nullopt;
  }
  if (state != gc::State::Ready && state != gc::State::Playing) return std::nullopt;

  // The halfway line: touched by any sole corner.
  for (const Eigen::Vector2d& c : truth.soleCorners)
    if (c.x() * own < halfwayEdge)
      return Call{PenaltyRule::HalfwayLine, format("a sole corner at (%.2f, %.2f) m", c.x(), c.y())};
  // Off the carpet of the own half: every sole corner beyond its side or end.
  const double carpetX = field_.length / 2 + field_.borderStripWidth, carpetY = field_.width / 2 + field_.borderStripWidth;
  const bool off = std::all_of(truth.soleCorners.begin(), truth.soleCorners.end(), [&](const Eigen::Vector2d& c) {
    return std::abs(c.y()) > carpetY || c.x() * own > carpetX;
  });
  if (off) return Call{PenaltyRule::LeavingTheField, format("torso at (%.2f, %.2f) m, off the carpet", truth.torso.x(), truth.torso.y())};

  // Fallen: the get-up must start within 5 s and the robot stand within 20 s, then stay up 10 s.
  const bool fallenNow = truth.tilt > params_.fallTilt || truth.height < params_.fallHeight;
  const bool uprightNow = truth.tilt < params_.upTilt && truth.height > params_.upHeight;
  if (fallenSince_ < 0 && fallenNow) {
    fallenSince_ = t;
    worstTilt_ = truth.tilt;
    lowest_ = truth.height;
    getUpStarted_ = false;
    standingSince_ = -1;
  }
  if (fallenSince_ >= 0) {
    if (!getUpStarted_) {
      worstTilt_ = std::max(worstTilt_, truth.tilt);
      lowest_ = std::min(lowest_, truth.height);
      getUpStarted_ = worstTilt_ - truth.tilt >= params_.getUpProgress || truth.height - lowest_ >= 0.05;
    }
    if (uprightNow) {
      if (standingSince_ < 0) standingSince_ = t;
      if (t - standingSince_ >= params_.uprightTime) fallenSince_ = -1;
    } else {
      standingSince_ = -1;
    }
  }
  if (fallenSince_ >= 0) {
    const double since = t - fallenSince_;
    if (!getUpStarted_ && since >= params_.getUpStart)
      return Call{PenaltyRule::FallenRobot, format("no get-up started %.1f s after the fall (tilt %.0f deg)", since, truth.tilt)};
    if (standingSince_ < 0 && since >= params_.getUpLimit)
      return Call{PenaltyRule::FallenRobot, format("not standing %.1f s after the fall (tilt %.0f deg, torso %.2f m high)", since, truth.tilt, truth.height)};
  }
  if (state != gc::State::Playing) {
    // Each rule of PLAYING counts from PLAYING: standing in READY and SET (as a robot must, at
    // its kick-off position) is no inactivity once play resumes after a global game stuck.
    inactiveSince_ = wideSince_ = inGoalSince_ = -1;
    return std::nullopt;
  }

  if (truth.handOnBall && fallenSince_ < 0)
    return Call{PenaltyRule::PlayingWithArms, format("a hand touched a ball, torso at (%.2f, %.2f) m", truth.torso.x(), truth.torso.y())};
  // Inside a goal.
  if (std::abs(truth.torso.x()) > field_.length / 2 + halfwayEdge && std::abs(truth.torso.y()) < field_.goalInnerWidth / 2) {
    if (inGoalSince_ < 0) inGoalSince_ = t;
    if (t - inGoalSince_ > params_.goalTime)
      return Call{PenaltyRule::GoalArea, format("inside the goal for %.1f s, torso at (%.2f, %.2f) m", t - inGoalSince_, truth.torso.x(), truth.torso.y())};
  } else {
    inGoalSince_ = -1;
  }
  if (fallenSince_ >= 0) {  // the fallen rule judges a robot on the ground
    inactiveSince_ = wideSince_ = -1;
    return std::nullopt;
  }
  if (truth.active) {
    inactiveSince_ = -1;
  } else {
    if (inactiveSince_ < 0) inactiveSince_ = t;
    if (t - inactiveSince_ >= params_.inactiveTime)
      return Call{PenaltyRule::InactiveRobot, format("no walking, turning or looking for the ball for %.1f s", t - inactiveSince_)};
  }
  const double stance = (truth.feet[0] - truth.feet[1]).norm();
  if (stance > params_.stanceWidth) {
    if (wideSince_ < 0) wideSince_ = t;
    if (t - wideSince_ > params_.stanceTime)
      return Call{PenaltyRule::PlayerStance, format("feet %.2f m apart for %.1f s", stance, t - wideSince_)};
  } else {
    wideSince_ = -1;
  }
  return std::nullopt;
}

}  // namespace nao::sim
