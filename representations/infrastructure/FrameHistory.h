#pragma once
// Motion to cognition: the last half second of joint angles, torso poses and odometry, one
// entry per motion cycle (FrameHistoryProvider), so that cognition can compute the camera
// matrix at an image's exposure time (ExposureCameraMatrixProvider) and move its models by the
// odometry between two images' exposures, rather than the times it runs.
#include <deque>

#include <Eigen/Geometry>

#include "robot/JointIds.h"
#include "robot/math/Pose2.h"

namespace nao {

struct FrameHistory {
  struct Entry {
    double time = 0;  // s, backend clock (SensorFrame::time)
    JointArray joints{};
    Eigen::Isometry3d robotToTorso = Eigen::Isometry3d::Identity();
    Pose2 odometry;  // Odometry::pose after this cycle's motion
    Eigen::Vector2d imuAngle = Eigen::Vector2d::Zero();  // the torso's roll and pitch (IMU), rad
  };
  std::deque<Entry> entries;  // oldest first

  // Joints and torso at time t: interpolated between the two entries around it (joints
  // linearly, the torso's rotation by slerp); the nearest entry outside the history's span.
  // False when the history is empty.
  bool at(double t, JointArray& joints, Eigen::Isometry3d& robotToTorso) const {
    if (entries.empty()) return false;
    std::size_t i = 1;
    while (i < entries.size() && entries[i].time < t) ++i;
    if (i == entries.size() || t <= entries.front().time) {
      const Entry& e = t <= entries.front().time ? entries.front() : entries.back();
      joints = e.joints;
      robotToTorso = e.robotToTorso;
      return true;
    }
    const Entry &a = entries[i - 1], &b = entries[i];
    const double span = b.time - a.time;
    const double s = span > 0 ? (t - a.time) / span : 1.0;
    for (int j = 0; j < NumJoints; ++j) joints[j] = a.joints[j] + s * (b.joints[j] - a.joints[j]);
    const Eigen::Quaterniond qa(a.robotToTorso.linear()), qb(b.robotToTorso.linear());
    robotToTorso.linear() = qa.slerp(s, qb).toRotationMatrix();
    robotToTorso.translation() = a.robotToTorso.translation() + s * (b.robotToTorso.translation() - a.robotToTorso.translation());
    return true;
  }

  // The IMU's roll and pitch at time t, interpolated as above (what a calibration sample of an
  // image taken at t needs). False when the history is empty.
  bool imuAngleAt(double t, Eigen::Vector2d& angle) const {
    if (entries.empty()) return false;
    std::size_t i = 1;
    while (i < entries.size() && entries[i].time < t) ++i;
    if (i == entries.size() || t <= entries.front().time) {
      angle = (t <= entries.front().time ? entries.front() : entries.back()).imuAngle;
      return true;
    }
    const Entry &a = entries[i - 1], &b = entries[i];
    const double span = b.time - a.time;
    const double s = span > 0 ? (t - a.time) / span : 1.0;
    angle = a.imuAngle + s * (b.imuAngle - a.imuAngle);
    return true;
  }

  // The odometry pose at time t, interpolated as above (the heading along the shorter way).
  // False when the history is empty.
  bool odometryAt(double t, Pose2& pose) const {
    if (entries.empty()) return false;
    std::size_t i = 1;
    while (i < entries.size() && entries[i].time < t) ++i;
    if (i == entries.size() || t <= entries.front().time) {
      pose = (t <= entries.front().time ? entries.front() : entries.back()).odometry;
      return true;
    }
    const Pose2 &a = entries[i - 1].odometry, &b = entries[i].odometry;
    const double span = entries[i].time - entries[i - 1].time;
    const double s = span > 0 ? (t - entries[i - 1].time) / span : 1.0;
    const Pose2 d = a.inverse() * b;
    pose = a * Pose2(s * d.x, s * d.y, s * d.theta);
    return true;
  }
};

}  // namespace nao
