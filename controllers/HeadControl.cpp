#include "controllers/HeadControl.h"

#include <algorithm>
#include <cmath>

#include "controllers/Kinematics.h"
#include "perception/Geometry.h"
#include "robot/ForwardKinematics.h"
#include "robot/RobotDimensions.h"

namespace nao {

const std::vector<CalibrationView>& HeadControl::calibrationPattern() {
  static const std::vector<CalibrationView> pattern = {
      {-40 * dims::kDeg, 0.1, CameraId::Top}, {0, 0.1, CameraId::Top}, {40 * dims::kDeg, 0.1, CameraId::Top},
      {-40 * dims::kDeg, 0.0, CameraId::Bottom}, {0, 0.0, CameraId::Bottom}, {40 * dims::kDeg, 0.0, CameraId::Bottom},
  };
  return pattern;
}

Eigen::Vector2d HeadControl::anglesToLookAt(const Eigen::Vector3d& pointRobot, CameraId camera,
                                            const Eigen::Isometry3d& robotToTorso) {
  const Eigen::Vector3d q = robotToTorso.inverse() * pointRobot - Eigen::Vector3d(0, 0, dims::kNeckZ);
  // The cameras sit in the head's xz plane: HeadYaw alone turns that plane onto the point.
  const double yaw = std::atan2(q.y(), q.x());
  const Eigen::Vector3d p = rotZ(-yaw) * q;  // (distance, 0, height) seen from the neck
  const bool top = camera == CameraId::Top;
  const Eigen::Vector3d mount(top ? dims::kTopCameraX : dims::kBottomCameraX, 0, top ? dims::kTopCameraZ : dims::kBottomCameraZ);
  const double mountPitch = top ? dims::kTopCameraPitch : dims::kBottomCameraPitch;
  // The optical axis Ry(pitch + mountPitch) e_x must point from the camera to the point; the
  // camera moves with the pitch, so iterate (the mount offset is small against the distance).
  double pitch = std::atan2(-p.z(), p.x()) - mountPitch;
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d d = p - rotY(pitch) * mount;
    pitch = std::atan2(-d.z(), d.x()) - mountPitch;
  }
  return {clampToLimits(HeadYaw, yaw), clampToLimits(HeadPitch, pitch)};
}

HeadJointRequest HeadControl::update(const SensorFrame& frame, const HeadMotionRequest& request,
                                     const Eigen::Isometry3d& robotToTorso) {
  const Eigen::Vector2d reading(frame.joints.position[HeadYaw], frame.joints.position[HeadPitch]);
  if (!initialized_) {
    initialized_ = true;
    command_ = reading;
    lastReading_ = reading;
    velocity_.setZero();
    lastTime_ = frame.time;
  }
  const double dt = std::clamp(frame.time - lastTime_, 0.0, 0.05);
  lastTime_ = frame.time;

  switch (request.mode) {
    case HeadMotionRequest::Mode::Angles: goal_ = {request.yaw, request.pitch}; break;
    case HeadMotionRequest::Mode::LookAtRobotPoint:
      goal_ = anglesToLookAt(request.point, request.camera, robotToTorso);
      break;
    case HeadMotionRequest::Mode::LookAtFieldPoint: {
      const Eigen::Vector2d xy = fieldToRobot(request.point.head<2>(), request.robotPose);
      goal_ = anglesToLookAt(Eigen::Vector3d(xy.x(), xy.y(), request.point.z()), request.camera, robotToTorso);
      break;
    }
    case HeadMotionRequest::Mode::Sweep: {
      const double amplitude = std::max(0.05, std::abs(request.sweepAmplitude));
      sweepPhase_ += std::max(0.0, request.sweepSpeed) * dt / amplitude;
      goal_ = {amplitude * std::sin(sweepPhase_), request.sweepPitch};
      break;
    }
    case HeadMotionRequest::Mode::Calibration: {
      const auto& pattern = calibrationPattern();
      const CalibrationView& v = pattern[std::min(request.calibrationIndex, pattern.size() - 1)];
      goal_ = {v.yaw, v.pitch};
      break;
    }
  }
  goal_ = {clampToLimits(HeadYaw, goal_.x()), clampToLimits(HeadPitch, goal_.y())};

  // Speed-limited motion with bounded acceleration, braking in time to stop at the goal.
  const double limit = request.maxSpeed > 0 ? request.maxSpeed : 1e9;
  const Eigen::Vector2d vmax(std::min(params_.maxYawSpeed, limit), std::min(params_.maxPitchSpeed, limit));
  for (int k = 0; k < 2; ++k) {
    const double e = goal_[k] - command_[k];
    const double brake = std::sqrt(2 * params_.maxAcceleration * std::abs(e));
    const double want = std::copysign(std::min(vmax[k], brake), e);
    velocity_[k] += std::clamp(want - velocity_[k], -params_.maxAcceleration * dt, params_.maxAcceleration * dt);
    const double step = velocity_[k] * dt;
    if (std::abs(step) >= std::abs(e) || std::abs(e) < 1e-4) {
      command_[k] = goal_[k];
      velocity_[k] = 0;
    } else {
      command_[k] += step;
    }
  }

  // Settled: commanded at the goal, the joints there and still.
  const double speed = dt > 0 ? (reading - lastReading_).norm() / dt : 0.0;
  lastReading_ = reading;
  const bool still = (command_ - goal_).norm() < 1e-6 && (reading - goal_).cwiseAbs().maxCoeff() < params_.arrivedTolerance &&
                     speed < params_.stillSpeed;
  if (!still) stillSince_ = -1;
  else if (stillSince_ < 0) stillSince_ = frame.time;
  settled_ = still && frame.time - stillSince_ >= params_.settleTime;

  HeadJointRequest out;
  out.yaw = command_.x();
  out.pitch = command_.y();
  out.stiffness = 0.8;
  return out;
}

}  // namespace nao
