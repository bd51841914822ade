#include "controllers/InertialOdometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

namespace nao {

namespace {

// Cycles in a row with every foot rejected after which the kinematics are taken as they are:
// the filter has lost track (a push the IMU clipped, a robot put down by hand), and the
// kinematics are the anchor.
constexpr int kMaxRejectedInARow = 25;

Eigen::Vector2d rotated(const Eigen::Vector2d& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

constexpr double kGravity = 9.81;

}  // namespace

Eigen::Vector2d ImuVelocityChange::update(const Eigen::Matrix3d& tilt, const Eigen::Vector3d& accelerometer,
                                          const Eigen::Vector3d& gyroscope, double turn, double dt, const Eigen::Vector3d& imu) {
  const Eigen::Vector3d specific = tilt * accelerometer - Eigen::Vector3d(0, 0, kGravity);
  const Eigen::Vector3d lever = tilt * gyroscope.cross(imu);
  const Eigen::Vector2d acceleration = rotated(specific.head<2>(), turn), leverNow = rotated(lever.head<2>(), turn);  // start frame
  const Eigen::Vector2d change = have_ && dt > 0 ? Eigen::Vector2d(0.5 * (lastAcceleration_ + acceleration) * dt - (leverNow - lastLever_))
                                                 : Eigen::Vector2d(Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN()));
  // The next cycle starts in this one's end frame.
  lastAcceleration_ = specific.head<2>();
  lastLever_ = lever.head<2>();
  have_ = specific.allFinite() && lever.allFinite();
  return change;
}

Eigen::Vector2d InertialOdometry::update(double dt, double turn, const Eigen::Vector2d& imuDelta,
                                         const Eigen::Vector2d& leftVelocity, double leftWeight,
                                         const Eigen::Vector2d& rightVelocity, double rightWeight) {
  leftWeight = std::clamp(std::isfinite(leftWeight) ? leftWeight : 0.0, 0.0, 1.0);
  rightWeight = std::clamp(std::isfinite(rightWeight) ? rightWeight : 0.0, 0.0, 1.0);
  const bool leftOk = leftWeight > 0 && leftVelocity.allFinite(), rightOk = rightWeight > 0 && rightVelocity.allFinite();
  const double r2 = params_.measurement * params_.measurement;
  const auto kinematic = [&] {
    const double wl = leftOk ? leftWeight : 0.0, wr = rightOk ? rightWeight : 0.0;
    return wl + wr > 0 ? Eigen::Vector2d((wl * (leftOk ? leftVelocity : Eigen::Vector2d::Zero()) +
                                          wr * (rightOk ? rightVelocity : Eigen::Vector2d::Zero())) /
                                         (wl + wr))
                       : Eigen::Vector2d::Zero();
  };
  if (!initialised_ || !(dt > 0) || !std::isfinite(turn) || !imuDelta.allFinite()) {
    // Start from the kinematics; the bias is unknown within initialBias (kept from before
    // when there is one: a gap in the readings does not change the sensor).
    velocity_ = kinematic();
    if (!initialised_ || !bias_.allFinite()) bias_.setZero();
    covariance_ << r2, 0, 0, params_.initialBias * params_.initialBias;
    initialised_ = true;
    rejectedInARow_ = 0;
    return velocity_;
  }
  // The velocity into this cycle's frame (it turns with the robot), then the prediction:
  // v += imuDelta - b dt. The bias is the body's (a tilt that is off, the sensor's offset): it
  // stays in the robot frame.
  velocity_ = rotated(velocity_, -turn);
  velocity_ += imuDelta - bias_ * dt;
  Eigen::Matrix2d f;
  f << 1, -dt, 0, 1;
  covariance_ = f * covariance_ * f.transpose();
  covariance_(0, 0) += params_.processVelocity * params_.processVelocity;
  covariance_(1, 1) += params_.processBias * params_.processBias;

  int accepted = 0, offered = 0;
  if (leftOk) {
    ++offered;
    accepted += measure(leftVelocity, leftWeight) ? 1 : 0;
  }
  if (rightOk) {
    ++offered;
    accepted += measure(rightVelocity, rightWeight) ? 1 : 0;
  }
  if (offered > 0 && accepted == 0 && ++rejectedInARow_ >= kMaxRejectedInARow) {
    velocity_ = kinematic();
    covariance_(0, 0) = r2;
    covariance_(0, 1) = covariance_(1, 0) = 0;
    rejectedInARow_ = 0;
  } else if (accepted > 0) {
    rejectedInARow_ = 0;
  }
  return velocity_;
}

bool InertialOdometry::measure(const Eigen::Vector2d& z, double weight) {
  const double r = params_.measurement * params_.measurement / weight;
  const double s = covariance_(0, 0) + r;
  const Eigen::Vector2d innovation = z - velocity_;
  // The innovation's two axes are independent with variance s each: |innovation|^2 / s is
  // chi-square with 2 degrees of freedom (a gate of 3 rejects 1.1 % of good measurements).
  // Written so that a NaN is rejected too.
  if (!(innovation.squaredNorm() <= params_.gate * params_.gate * s)) {
    ++rejected_;
    return false;
  }
  const double kv = covariance_(0, 0) / s, kb = covariance_(1, 0) / s;
  velocity_ += kv * innovation;
  bias_ += kb * innovation;
  const Eigen::Matrix2d p = covariance_;
  covariance_(0, 0) = p(0, 0) - kv * p(0, 0);
  covariance_(0, 1) = p(0, 1) - kv * p(0, 1);
  covariance_(1, 0) = p(1, 0) - kb * p(0, 0);
  covariance_(1, 1) = p(1, 1) - kb * p(0, 1);
  return true;
}

}  // namespace nao
