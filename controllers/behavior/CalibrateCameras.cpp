#include "controllers/behavior/CalibrateCameras.h"

#include <cmath>

namespace nao::behavior {

namespace {
constexpr double kDeg = M_PI / 180;

}  // namespace

CalibrateCameras::CalibrateCameras(const FieldDimensions& field, const JointArray& standPosture, const Params& params)
    : field_(field), stand_(standPosture), params_(params) {}

void CalibrateCameras::restart(double time) {
  machine_.state = State::Done;  // so that go() records the time
  machine_.go(State::Localize, time);
  views_.clear();
  current_ = 0;
  round_ = 0;
  summary_ = {};
  sideVotes_ = {};
  lastVoteImage_ = -1;
}

int CalibrateCameras::decideSide(const BehaviorInput& in, const CameraPercepts& percepts) {
  // A goal box side in view: its short line's middle to the right means the left side line.
  if (percepts.processed && percepts.timestamp != lastVoteImage_ && percepts.goalBoxSide.found) {
    lastVoteImage_ = percepts.timestamp;
    const int s = percepts.goalBoxSide.shortLine;
    if (s >= 0 && s < static_cast<int>(percepts.lines.size())) {
      const Eigen::Vector2d middle = (percepts.lines[s].from + percepts.lines[s].to) / 2;
      if (middle.x() > 0.3 && middle.norm() < 5.0 && std::abs(middle.y()) > 0.2) ++sideVotes_[middle.y() < 0 ? 0 : 1];
    }
  }
  const double waited = machine_.timeIn(in.time);
  if (waited < params_.settleTime) return 0;
  const int votes = sideVotes_[0] + sideVotes_[1];
  if (votes >= params_.sideVotes) {
    summary_.sideFrom = "goal box";
    if (sideVotes_[0] >= params_.sideShare * votes) return 1;
    if (sideVotes_[1] >= params_.sideShare * votes) return -1;
  }
  summary_.sideFrom = "localization";
  if (waited < params_.sideTimeout || !in.pose.valid) return 0;
  // The field is point symmetric and the rules' start is in the own half: a pose in the other
  // half is the mirror of the true one (eval calibration seed 41: dark, no box seen, the pose
  // settled at (2.66, 3.19) for a start at (-3.2, -3) and the robot calibrated the wrong corner).
  const double y = in.pose.pose.x > 0 ? -in.pose.pose.y : in.pose.pose.y;
  return y >= 0 ? 1 : -1;
}

void CalibrateCameras::planFrom(int sideSign, const RobotPose& pose) {
  // The own goal box's side on the start's side line is the one to look at.
  summary_.side = sideSign;
  side_ = calibration::ownGoalBoxSide(field_, sideSign);
  position_ = calibration::calibrationPosition(side_);
  // The rules' start is known: the odometry from it beats the uncalibrated localization (whose
  // distances the camera offsets distort) on the way to the box.
  const Eigen::Vector3d start = calibration::initialPosition(field_, sideSign);
  startPose_ = Pose2(start.x(), start.y(), start.z());
  startOdometry_ = pose.odometry;
  // Aligning looks at the box side as the plan's straight top view from there does.
  for (const calibration::CalibrationView& v : calibration::planViews(side_, position_.head<2>(), stand_))
    if (v.camera == CameraId::Top && std::abs(v.headYaw) < 1e-6) alignPitch_ = v.headPitch;
}

Pose2 CalibrateCameras::turnTarget(double heading) const {
  return anchor_.odometry * Pose2(0, 0, Pose2::wrap(heading - anchor_.pose.theta));
}

Pose2 CalibrateCameras::viewTarget(const Eigen::Vector3d& robotPose) const {
  // At the anchor: a turn in place (exactly, as before the far views).
  if ((robotPose.head<2>() - Eigen::Vector2d(anchor_.pose.x, anchor_.pose.y)).norm() < 1e-9) return turnTarget(robotPose.z());
  return anchor_.odometry * (anchor_.pose.inverse() * Pose2(robotPose.x(), robotPose.y(), robotPose.z()));
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

RobotPose CalibrateCameras::byOdometry(const RobotPose& pose) const {
  RobotPose here = pose;
  here.pose = startPose_ * (startOdometry_.inverse() * pose.odometry);
  return here;
}

void CalibrateCameras::planViewsFromHere(const RobotPose& here, bool aligned, double time, Output& out) {
  // Aligned with the box, the robot stands at the calibration position; else where it believes
  // it stands. The views' headings become turns from here on odometry.
  anchor_ = here;
  if (aligned) anchor_.pose = Pose2(position_.x(), position_.y(), position_.z());
  views_.clear();
  const Eigen::Vector2d at(anchor_.pose.x, anchor_.pose.y);
  for (const calibration::CalibrationView& v : calibration::planViews(side_, at, stand_)) views_.push_back({v, 0, false});
  if (params_.farDistance > 0) {
    // The far views: farDistance from the short line's middle, on the line from it through here.
    calibration::ViewPlanOptions far;
    far.distance = params_.farDistance;
    far.topYawsDeg.clear();
    for (int k = 0; k < params_.farPans; ++k) far.topYawsDeg.push_back(-45 + 90.0 * k / (params_.farPans - 1));
    far.bottomYawsDeg = far.topYawsDeg;
    const Eigen::Vector2d away = (at - side_.middle()).normalized();
    const Eigen::Vector2d there = side_.middle() + params_.farDistance * away;
    for (const calibration::CalibrationView& v : calibration::planViews(side_, there, stand_, far)) views_.push_back({v, 0, false});
  }
  current_ = 0;
  nextView(time, out);
}

void CalibrateCameras::align(const BehaviorInput& in, const CameraPercepts& percepts, Output& out) {
  const double t = in.time;
  out.lookActive = false;
  out.head.mode = HeadMotionRequest::Mode::Angles;
  out.head.pitch = alignPitch_;
  out.head.yaw = 0;
  if (alignWalking_) {
    out.motion.motion = MotionType::WalkTo;
    out.motion.walkTarget = alignTarget_;
    out.motion.walkTargetInOdometry = true;
    out.motion.walkTargetId = walkId_;
    if (t - alignSince_ >= params_.turnSettle && in.motion.walkToReached) {
      alignWalking_ = false;
      alignSince_ = t;
      alignImages_ = 0;
      alignMiddle_ = alignDirection_ = Eigen::Vector2d::Zero();
    }
    return;
  }
  out.motion = MotionRequest{};
  if (t - alignSince_ < params_.alignLook) return;
  // The short line: ahead within reach, roughly square to the view.
  if (percepts.camera == CameraId::Top && percepts.processed) {
    for (const LinesPercept::Line& l : percepts.lines) {
      const Eigen::Vector2d middle = (l.from + l.to) / 2;
      Eigen::Vector2d d = l.to - l.from;
      if (d.norm() < 0.2 || middle.x() < 0.4 || middle.x() > 2.0 || std::abs(middle.y()) > 0.8) continue;
      d.normalize();
      if (d.y() < 0) d = -d;  // one orientation: along +y
      if (std::abs(d.x()) > std::sin(0.5)) continue;  // not square to the view
      alignMiddle_ += middle;
      alignDirection_ += d;
      ++alignImages_;
      break;
    }
  }
  if (t - alignSince_ < params_.alignLook + params_.alignGather) return;
  if (alignImages_ == 0 || alignStep_ >= params_.alignSteps) {
    planViewsFromHere(byOdometry(in.pose), false, t, out);  // no line in view (or enough tries): go on from here
    return;
  }
  const Eigen::Vector2d middle = alignMiddle_ / alignImages_;
  const Eigen::Vector2d along = alignDirection_.normalized();
  // The calibration position: `distance` from the middle, on the robot's side of the line,
  // facing the middle.
  Eigen::Vector2d normal(along.y(), -along.x());  // points away from the robot (+x side)
  if (normal.dot(middle) < 0) normal = -normal;
  const double distance = (position_.head<2>() - side_.middle()).norm();
  const Eigen::Vector2d goal = middle - distance * normal;
  const double heading = std::atan2(normal.y(), normal.x());
  if (goal.norm() < params_.alignDistance && std::abs(heading) < params_.alignAngle) {
    summary_.aligned = true;
    planViewsFromHere(byOdometry(in.pose), true, t, out);
    return;
  }
  // Walk there, in the odometry frame at this image's time.
  ++alignStep_;
  ++summary_.alignSteps;
  ++walkId_;
  alignTarget_ = in.pose.odometry * Pose2(goal.x(), goal.y(), heading);
  alignWalking_ = true;
  alignSince_ = t;
  out.motion.motion = MotionType::WalkTo;
  out.motion.walkTarget = alignTarget_;
  out.motion.walkTargetInOdometry = true;
  out.motion.walkTargetId = walkId_;
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
                                               const CameraCalibration& current, const CameraPercepts& percepts) {
  Output out;
  out.head.maxSpeed = params_.headMaxSpeed;
  const double t = in.time;
  auto stand = [&] { out.motion = MotionRequest{}; };
  auto turnAndAim = [&](const PlannedView& p) {
    out.motion.motion = MotionType::WalkTo;
    out.motion.walkTarget = viewTarget(p.view.robotPose);
    out.motion.walkTargetInOdometry = true;
    out.motion.walkTargetId = walkId_;
    out.lookActive = false;
    out.head.mode = HeadMotionRequest::Mode::Angles;
    out.head.yaw = p.view.headYaw;
    out.head.pitch = p.view.headPitch;
  };
  switch (machine_.state) {
    case State::Localize: {
      stand();
      // First ahead, where a goal box side is in view from either start; then the usual look
      // around, which the localization needs (a fixed view of the box alone misleads it).
      if (machine_.timeIn(t) < params_.sideTimeout) {
        out.lookActive = false;
        out.head.mode = HeadMotionRequest::Mode::Angles;
        out.head.yaw = 0;
        out.head.pitch = params_.sideLookPitch;
      }
      if (const int sideSign = decideSide(in, percepts)) {
        planFrom(sideSign, in.pose);
        ++walkId_;
        machine_.go(State::GoToPosition, t);
      }
      break;
    }
    case State::GoToPosition: {
      // On odometry from the start to the calibration position.
      out.motion.motion = MotionType::WalkTo;
      out.motion.walkTarget = startOdometry_ * (startPose_.inverse() * Pose2(position_.x(), position_.y(), position_.z()));
      out.motion.walkTargetInOdometry = true;
      out.motion.walkTargetId = walkId_;
      if (machine_.timeIn(t) >= params_.turnSettle && in.motion.walkToReached) {
        alignStep_ = 0;
        alignWalking_ = false;
        alignSince_ = t;
        alignImages_ = 0;
        alignMiddle_ = alignDirection_ = Eigen::Vector2d::Zero();
        machine_.go(State::Align, t);
      }
      break;
    }
    case State::Align:
      align(in, percepts, out);
      break;
    case State::Turn: {
      turnAndAim(views_[current_]);
      // Turned: collect at once (the calibrator waits for the head and torso to hold still).
      if (machine_.timeIn(t) >= params_.turnSettle && in.motion.walkToReached) machine_.go(State::Collect, t);
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
