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
    const Bracket k = bracket(t);
    if (k.a == k.b) {
      joints = k.a->joints;
      robotToTorso = k.a->robotToTorso;
      return true;
    }
    const Entry &a = *k.a, &b = *k.b;
    for (int j = 0; j < NumJoints; ++j) joints[j] = a.joints[j] + k.s * (b.joints[j] - a.joints[j]);
    const Eigen::Quaterniond qa(a.robotToTorso.linear()), qb(b.robotToTorso.linear());
    robotToTorso.linear() = qa.slerp(k.s, qb).toRotationMatrix();
    robotToTorso.translation() = a.robotToTorso.translation() + k.s * (b.robotToTorso.translation() - a.robotToTorso.translation());
    return true;
  }

  // The IMU's roll and pitch at time t, interpolated as above (what a calibration sample of an
  // image taken at t needs). False when the history is empty.
  bool imuAngleAt(double t, Eigen::Vector2d& angle) const {
    if (entries.empty()) return false;
    const Bracket k = bracket(t);
    angle = k.a == k.b ? k.a->imuAngle : Eigen::Vector2d(k.a->imuAngle + k.s * (k.b->imuAngle - k.a->imuAngle));
    return true;
  }

  // The odometry pose at time t, interpolated as above (the heading along the shorter way).
  // False when the history is empty.
  bool odometryAt(double t, Pose2& pose) const {
    if (entries.empty()) return false;
    const Bracket k = bracket(t);
    if (k.a == k.b) {
      pose = k.a->odometry;
      return true;
    }
    const Pose2 d = k.a->odometry.inverse() * k.b->odometry;
    pose = k.a->odometry * Pose2(k.s * d.x, k.s * d.y, k.s * d.theta);
    return true;
  }

 private:
  // The entries around t and t's fraction between them; outside the span both are the nearest
  // entry. The history must not be empty.
  struct Bracket {
    const Entry *a, *b;
    double s;
  };
  Bracket bracket(double t) const {
    std::size_t i = 1;
    while (i < entries.size() && entries[i].time < t) ++i;
    if (i == entries.size() || t <= entries.front().time) {
      const Entry* e = t <= entries.front().time ? &entries.front() : &entries.back();
      return {e, e, 0.0};
    }
    const Entry &a = entries[i - 1], &b = entries[i];
    const double span = b.time - a.time;
    return {&a, &b, span > 0 ? (t - a.time) / span : 1.0};
  }
};

}  // namespace nao
