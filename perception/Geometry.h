#pragma once
// Small 2-D pose helpers between the field frame and the robot frame (docs/conventions.md).
// A robot pose is (x, y, theta): the robot frame in the field frame.
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

namespace nao {

// A field-frame point in the robot frame.
inline Eigen::Vector2d fieldToRobot(const Eigen::Vector2d& pField, const Eigen::Vector3d& robotPose) {
  const double c = std::cos(robotPose.z()), s = std::sin(robotPose.z());
  const double dx = pField.x() - robotPose.x(), dy = pField.y() - robotPose.y();
  return {c * dx + s * dy, -s * dx + c * dy};
}

// A robot-frame point in the field frame.
inline Eigen::Vector2d robotToField(const Eigen::Vector2d& pRobot, const Eigen::Vector3d& robotPose) {
  const double c = std::cos(robotPose.z()), s = std::sin(robotPose.z());
  return {robotPose.x() + c * pRobot.x() - s * pRobot.y(), robotPose.y() + s * pRobot.x() + c * pRobot.y()};
}

// T_field_robot as a 3-D transform (rotation about z by theta).
inline Eigen::Isometry3d robotPoseToIsometry(const Eigen::Vector3d& robotPose) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::AngleAxisd(robotPose.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  t.translation() = Eigen::Vector3d(robotPose.x(), robotPose.y(), 0);
  return t;
}

// Angle wrapped to (-pi, pi].
inline double normalizeAngle(double a) {
  constexpr double pi = std::numbers::pi;
  a = std::remainder(a, 2 * pi);
  return a <= -pi ? a + 2 * pi : a;
}

}  // namespace nao
