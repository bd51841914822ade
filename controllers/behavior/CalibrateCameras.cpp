#include "controllers/behavior/CalibrateCameras.h"

#include <cmath>

namespace nao::behavior {

namespace {
constexpr double kDeg = M_PI / 180;

GoToPose::Params goToParams(const CalibrateCameras::Params& p) {
  GoToPose::Params g;
  g.arrivedDistance = p.arrivedDistance;
  g.arrivedAngle = p.arrivedAngle;
  return g;
}
}  // namespace

CalibrateCameras::CalibrateCameras(const FieldDimensions& field, const JointArray& standPosture, const Params& params)
    : field_(field), stand_(standPosture), params_(params), goTo_(goToParams(params)) {}

void CalibrateCameras::restart(double time) {
  machine_.state = State::Done;  // so that go() records the time
  machine_.go(State::Localize, time);
  views_.clear();
  current_ = 0;
  round_ = 0;
  summary_ = {};
  goTo_ = GoToPose(goToParams(params_));
}

void CalibrateCameras::planFrom(const RobotPose& pose) {
  // The start is on one of the side lines: the estimate's y says which; the own goal box's side
  // there is the one to look at.
  const int sideSign = pose.pose.y >= 0 ? 1 : -1;
  side_ = calibration::ownGoalBoxSide(field_, sideSign);
  position_ = calibration::calibrationPosition(side_);
  views_.clear();
  for (const calibration::CalibrationView& v : calibration::planViews(side_, position_.head<2>(), stand_))
    views_.push_back({v, 0, false});
}

Pose2 CalibrateCameras::turnTarget(double heading) const {
  return anchor_.odometry * Pose2(0, 0, Pose2::wrap(heading - anchor_.pose.theta));
}

void CalibrateCameras::nextView(double time, Output& out) {
  while (current_ < views_.size() && views_[current_].taken) ++current_;
  if (current_ >= views_.size()) {
    ++round_;
    summary_.rounds = round_;
    solutionWanted_ = 0;  // set on entering Solve
    machine_.go(State::Solve, time);
    return;
  }
  views_[current_].viewId = nextViewId_++;
  ++walkId_;
  machine_.go(State::Turn, time);
  (void)out;
}

void CalibrateCameras::startRound(double time, Output& out) {
  // The rejected views once more, their pans moved (alternately to either side): another view
  // of the box where the first one was unusable.
  const double shift = (round_ % 2 ? 1 : -1) * params_.retakePanDeg * kDeg;
  std::vector<PlannedView> retakes;
  for (const PlannedView& p : views_)
    if (!p.taken) retakes.push_back(p);
  if (retakes.empty()) retakes = views_;  // all were taken, yet the solve failed: take them all again
  for (PlannedView& p : retakes) {
    p.view.headYaw += shift;
    p.view.robotPose.z() -= shift;  // the body turns the other way: the box stays in view
    p.taken = false;
  }
  views_ = retakes;
  current_ = 0;
  nextView(time, out);
}

CalibrateCameras::Output CalibrateCameras::run(const BehaviorInput& in, const CalibrationStatus& status,
                                               const CameraCalibration& current) {
  Output out;
  out.head.maxSpeed = params_.headMaxSpeed;
  const double t = in.time;
  auto stand = [&] { out.motion = MotionRequest{}; };
  auto turnAndAim = [&](const PlannedView& p) {
    out.motion.motion = MotionType::WalkTo;
    out.motion.walkTarget = turnTarget(p.view.robotPose.z());
    out.motion.walkTargetInOdometry = true;
    out.motion.walkTargetId = walkId_;
    out.lookActive = false;
    out.head.mode = HeadMotionRequest::Mode::Angles;
    out.head.yaw = p.view.headYaw;
    out.head.pitch = p.view.headPitch;
  };
  switch (machine_.state) {
    case State::Localize:
      stand();
      if (in.pose.valid && machine_.timeIn(t) >= params_.settleTime) {
        planFrom(in.pose);
        machine_.go(State::GoToPosition, t);
      }
      break;
    case State::GoToPosition:
      if (goTo_.run(in, Pose2(position_.x(), position_.y(), position_.z()), out.motion)) {
        anchor_ = in.pose;
        // Plan again from where it believes it stands now: the headings aim at the box from here.
        views_.clear();
        for (const calibration::CalibrationView& v :
             calibration::planViews(side_, Eigen::Vector2d(in.pose.pose.x, in.pose.pose.y), stand_))
          views_.push_back({v, 0, false});
        current_ = 0;
        nextView(t, out);
      }
      break;
    case State::Turn:
    case State::Aim: {
      const PlannedView& p = views_[current_];
      turnAndAim(p);
      if (machine_.state == State::Turn && machine_.timeIn(t) >= params_.turnSettle && in.motion.walkToReached)
        machine_.go(State::Aim, t);
      // The head is at the view's angles once the calibrator finds it still: collect at once.
      if (machine_.state == State::Aim) machine_.go(State::Collect, t);
      break;
    }
    case State::Collect: {
      PlannedView& p = views_[current_];
      turnAndAim(p);
      out.calibration.action = CalibrationRequest::Action::Collect;
      out.calibration.viewId = p.viewId;
      out.calibration.camera = p.view.camera;
      const bool answered = status.last.viewId == p.viewId;
      if (answered || machine_.timeIn(t) >= params_.collectTimeout) {
        ++summary_.views;
        p.taken = answered && status.last.accepted;
        if (p.taken) ++summary_.accepted;
        ++current_;
        nextView(t, out);
      }
      break;
    }
    case State::Solve:
      stand();
      out.lookActive = false;
      if (solutionWanted_ == 0) solutionWanted_ = status.solutionId + 1;
      out.calibration.action = CalibrationRequest::Action::Solve;
      out.calibration.solutionId = solutionWanted_;
      if (status.solutionId == solutionWanted_) {
        if (status.accepted) {
          appliedBefore_ = status.appliedId;
          machine_.go(State::Apply, t);
        } else if (round_ >= params_.maxRounds) {
          out.report = "Calibration finished";
          machine_.go(State::Report, t);
        } else {
          startRound(t, out);
        }
      } else if (machine_.timeIn(t) >= params_.solveTimeout) {
        out.report = "Calibration finished";
        machine_.go(State::Report, t);
      }
      break;
    case State::Apply:
      stand();
      out.lookActive = false;
      out.calibration.action = CalibrationRequest::Action::Apply;
      out.calibration.solutionId = solutionWanted_;
      // Applied once the motion side uses it: the camera calibration this board sees is the new one.
      if (status.appliedId != appliedBefore_ && current.toArray() == status.applied.toArray()) {
        summary_.applied = true;
        // The check view: the top camera at the pan nearest straight ahead, as planned.
        std::size_t best = 0;
        for (std::size_t k = 0; k < views_.size(); ++k)
          if (views_[k].view.camera == CameraId::Top &&
              (views_[best].view.camera != CameraId::Top ||
               std::abs(views_[k].view.headYaw) < std::abs(views_[best].view.headYaw)))
            best = k;
        if (views_.empty()) {
          out.report = "Calibration finished";
          machine_.go(State::Report, t);
          break;
        }
        PlannedView check = views_[best];
        check.viewId = nextViewId_++;
        check.taken = false;
        views_.push_back(check);
        current_ = views_.size() - 1;
        ++walkId_;
        machine_.go(State::Verify, t);
      } else if (machine_.timeIn(t) >= params_.solveTimeout) {
        out.report = "Calibration finished";
        machine_.go(State::Report, t);
      }
      break;
    case State::Verify: {
      const PlannedView& p = views_[current_];
      turnAndAim(p);
      const bool turned = machine_.timeIn(t) >= params_.turnSettle && in.motion.walkToReached;
      if (turned) {
        out.calibration.action = CalibrationRequest::Action::Verify;
        out.calibration.viewId = p.viewId;
        out.calibration.camera = p.view.camera;
      }
      if (status.verifyAngleDeg >= 0 || machine_.timeIn(t) >= params_.collectTimeout + 3.0) {
        summary_.verifyAngleDeg = status.verifyAngleDeg;
        out.report = "Calibration finished";
        machine_.go(State::Report, t);
      }
      break;
    }
    case State::Report:
    case State::Done:
      stand();
      out.lookActive = false;
      out.head.mode = HeadMotionRequest::Mode::Angles;  // head straight: the referee sees a still robot
      break;
  }
  return out;
}

}  // namespace nao::behavior
