#include "controllers/behavior/LookActive.h"

#include <cmath>

#include <Eigen/Dense>

namespace nao::behavior {

LookActive::LookActive(const FieldModel& field, const Params& params) : params_(params) {
  for (const auto& i : field.intersections) features_.push_back({i.position});
  for (const auto& p : field.penaltyCrosses) features_.push_back({p});
  features_.push_back({field.centerCircleCenter});
  for (const auto& line : field.lines) {
    const Eigen::Vector2d d = line.to - line.from;
    const double length = d.norm();
    if (length < 1e-6) continue;
    const Eigen::Vector2d normal(-d.y() / length, d.x() / length);
    const int n = std::max(1, static_cast<int>(length / params_.lineSampleSpacing));
    for (int k = 0; k < n; ++k) features_.push_back({line.from + d * ((k + 0.5) / n), true, normal});
  }
}

double LookActive::informationGain(const Feature& f, const Pose2& pose, const Eigen::Matrix3d& cov) const {
  const Eigen::Vector2d rel = pose.inverse() * f.position;  // robot frame
  const double distance = rel.norm();
  if (distance < params_.minDistance || distance > params_.maxDistance) return 0;
  if (std::abs(std::atan2(rel.y(), rel.x())) > params_.maxYaw) return 0;
  // The measured relative position z = R(theta)^T (f - p): its Jacobian by (x, y, theta).
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  Eigen::Matrix<double, 2, 3> H;
  H << -c, -s, rel.y(), s, -c, -rel.x();
  const double sigma = params_.sigmaBase + params_.sigmaPerMetre * distance;
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  if (f.onLine) {
    // Only across the line: the normal in the robot frame.
    const Eigen::Vector2d n(c * f.normal.x() + s * f.normal.y(), -s * f.normal.x() + c * f.normal.y());
    const Eigen::RowVector3d h = n.transpose() * H;
    information = h.transpose() * h / (sigma * sigma);
  } else {
    information = H.transpose() * H / (sigma * sigma);
  }
  const Eigen::Matrix3d P = 0.5 * (cov + cov.transpose()) + 1e-9 * Eigen::Matrix3d::Identity();
  // det(P) / det(P_post) = det(I + P * information).
  const double ratio = (Eigen::Matrix3d::Identity() + P * information).determinant();
  return ratio > 1 ? 0.5 * std::log(ratio) : 0;
}

int LookActive::choose(const Pose2& pose, const Eigen::Matrix3d& cov, double currentYaw, int skip) const {
  int best = -1;
  double bestScore = 0;
  for (int i = 0; i < static_cast<int>(features_.size()); ++i) {
    if (i == skip) continue;
    const double gain = informationGain(features_[i], pose, cov);
    if (gain <= 0) continue;
    const Eigen::Vector2d rel = pose.inverse() * features_[i].position;
    const double score = gain - params_.yawCost * std::abs(std::atan2(rel.y(), rel.x()) - currentYaw);
    if (best < 0 || score > bestScore) {
      best = i;
      bestScore = score;
    }
  }
  return best;
}

void LookActive::lookAt(const Eigen::Vector2d& field, const Pose2& pose, HeadMotionRequest& request) const {
  request = HeadMotionRequest{};
  request.mode = HeadMotionRequest::Mode::LookAtFieldPoint;
  request.point = Eigen::Vector3d(field.x(), field.y(), 0);
  request.robotPose = Eigen::Vector3d(pose.x, pose.y, pose.theta);
  request.camera = CameraId::Top;
  request.maxSpeed = params_.maxHeadSpeed;
}

void LookActive::run(const BehaviorInput& in, HeadMotionRequest& request) {
  const double t = in.time;
  const bool poseValid = in.pose.valid;
  // A known ball is tracked; while the robot does not know where it is, only a near one (a far
  // ball in the middle of the view would keep the head from the field features it needs).
  const bool ballKnown = in.ball.valid && !in.ball.lost && t - in.ball.seenTime < params_.ballRecent &&
                         (poseValid || in.ball.position.norm() < params_.ballNearWhileLost);

  if (ballKnown && poseValid && in.pose.sigmaTranslation() > params_.glanceSigma && t - lastGlance_ > params_.glanceEvery)
    machine_.go(State::Glance, t);
  if (machine_.state == State::Glance && (machine_.timeIn(t) > params_.glanceFor || !poseValid)) {
    lastGlance_ = t;
    machine_.go(ballKnown ? State::TrackBall : State::LookAtFeature, t);
  }
  if (machine_.state != State::Glance) {
    if (ballKnown) machine_.go(State::TrackBall, t);
    else if (poseValid) machine_.go(State::LookAtFeature, t);
    else machine_.go(State::Sweep, t);
  }

  switch (machine_.state) {
    case State::TrackBall: {
      request = HeadMotionRequest{};
      request.mode = HeadMotionRequest::Mode::LookAtRobotPoint;
      request.point = Eigen::Vector3d(in.ball.position.x(), in.ball.position.y(), 0.05);
      request.camera = in.ball.position.norm() < params_.bottomCameraDistance ? CameraId::Bottom : CameraId::Top;
      request.maxSpeed = params_.maxHeadSpeed;
      target_ = -1;
      break;
    }
    case State::Glance:
    case State::LookAtFeature: {
      const bool due = target_ < 0 || t - targetSince_ > params_.dwell ||
                       informationGain(features_[target_], in.pose.pose, in.pose.covariance) <= 0;
      if (due) {
        double currentYaw = 0;
        if (target_ >= 0) {
          const Eigen::Vector2d rel = in.pose.pose.inverse() * features_[target_].position;
          currentYaw = std::atan2(rel.y(), rel.x());
        }
        // The one just looked at is skipped: its information is in the filter now.
        const int next = choose(in.pose.pose, in.pose.covariance, currentYaw, target_);
        if (next >= 0 || target_ < 0) {
          target_ = next;
          targetSince_ = t;
        }
      }
      if (target_ >= 0) {
        lookAt(features_[target_].position, in.pose.pose, request);
        break;
      }
      [[fallthrough]];  // nothing in reach: sweep
    }
    case State::Sweep:
      request = HeadMotionRequest{};
      request.mode = HeadMotionRequest::Mode::Sweep;
      request.sweepAmplitude = params_.sweepAmplitude;
      request.sweepPitch = params_.sweepPitch;
      request.sweepSpeed = params_.sweepSpeed;
      request.maxSpeed = params_.maxHeadSpeed;
      target_ = -1;
      break;
  }
}

}  // namespace nao::behavior
