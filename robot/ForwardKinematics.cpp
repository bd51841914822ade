#include "robot/ForwardKinematics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "robot/RobotDimensions.h"

namespace nao {

using Eigen::Isometry3d;
using Eigen::Matrix3d;
using Eigen::Vector3d;

Matrix3d rotX(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Matrix3d r;
  r << 1, 0, 0, 0, c, -s, 0, s, c;
  return r;
}
Matrix3d rotY(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Matrix3d r;
  r << c, 0, s, 0, 1, 0, -s, 0, c;
  return r;
}
Matrix3d rotZ(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Matrix3d r;
  r << c, -s, 0, s, c, 0, 0, 0, 1;
  return r;
}

namespace {

Isometry3d translation(double x, double y, double z) {
  Isometry3d t = Isometry3d::Identity();
  t.translation() = Vector3d(x, y, z);
  return t;
}
Isometry3d rotation(const Matrix3d& r) {
  Isometry3d t = Isometry3d::Identity();
  t.linear() = r;
  return t;
}

}  // namespace

Isometry3d torsoToHead(const JointArray& j) {
  Isometry3d t = Isometry3d::Identity();
  t.translation() = Vector3d(0, 0, dims::kNeckZ);
  t.linear() = rotZ(j[HeadYaw]) * rotY(j[HeadPitch]);
  return t;
}

Isometry3d headToCamera(CameraId camera) {
  Isometry3d t = Isometry3d::Identity();
  if (camera == CameraId::Top) {
    t.translation() = Vector3d(dims::kTopCameraX, 0, dims::kTopCameraZ);
    t.linear() = rotY(dims::kTopCameraPitch);
  } else {
    t.translation() = Vector3d(dims::kBottomCameraX, 0, dims::kBottomCameraZ);
    t.linear() = rotY(dims::kBottomCameraPitch);
  }
  return t;
}

Isometry3d torsoToCamera(const JointArray& joints, CameraId camera) {
  return torsoToHead(joints) * headToCamera(camera);
}

Isometry3d torsoToAnkle(const JointArray& j, BodySide side) {
  const bool left = side == BodySide::Left;
  const double sign = left ? 1.0 : -1.0;
  // Left axis (0, 1, -1)/sqrt2, right (0, 1, 1)/sqrt2; one motor drives both with one angle.
  const Vector3d hypAxis = Vector3d(0, 1, -sign).normalized();
  const double hipRoll = j[left ? LHipRoll : RHipRoll];
  const double hipPitch = j[left ? LHipPitch : RHipPitch];
  const double knee = j[left ? LKneePitch : RKneePitch];
  const double anklePitch = j[left ? LAnklePitch : RAnklePitch];
  const double ankleRoll = j[left ? LAnkleRoll : RAnkleRoll];

  Isometry3d t = translation(0, sign * dims::kHipY, 0);
  t.linear() = Eigen::AngleAxisd(j[LHipYawPitch], hypAxis).toRotationMatrix() * rotX(hipRoll) *
               rotY(hipPitch);
  t = t * translation(0, 0, -dims::kThighLength) * rotation(rotY(knee)) *
      translation(0, 0, -dims::kTibiaLength) * rotation(rotY(anklePitch) * rotX(ankleRoll));
  return t;
}

Isometry3d torsoToSole(const JointArray& joints, BodySide side) {
  return torsoToAnkle(joints, side) * translation(0, 0, -dims::kFootHeight);
}

Isometry3d torsoToHand(const JointArray& j, BodySide side) {
  const bool left = side == BodySide::Left;
  const double sign = left ? 1.0 : -1.0;
  const double shoulderPitch = j[left ? LShoulderPitch : RShoulderPitch];
  const double shoulderRoll = j[left ? LShoulderRoll : RShoulderRoll];
  const double elbowYaw = j[left ? LElbowYaw : RElbowYaw];
  const double elbowRoll = j[left ? LElbowRoll : RElbowRoll];
  const double wristYaw = j[left ? LWristYaw : RWristYaw];
  return translation(0, sign * dims::kShoulderY, dims::kShoulderZ) *
         rotation(rotY(shoulderPitch) * rotZ(shoulderRoll)) *
         translation(dims::kUpperArmLength, sign * dims::kElbowOffsetY, 0) *
         rotation(rotX(elbowYaw) * rotZ(elbowRoll)) * translation(dims::kLowerArmLength, 0, 0) *
         rotation(rotX(wristYaw)) * translation(dims::kHandOffsetX, 0, dims::kHandOffsetZ);
}

Matrix3d torsoTilt(double roll, double pitch) { return rotY(pitch) * rotX(roll); }

double torsoHeightAboveGround(const JointArray& joints, double roll, double pitch,
                              SoleContact contact) {
  const Matrix3d tilt = torsoTilt(roll, pitch);
  double lowest = std::numeric_limits<double>::infinity();
  for (BodySide side : {BodySide::Left, BodySide::Right}) {
    const Isometry3d sole = torsoToSole(joints, side);
    const Vector3d centre = tilt * sole.translation();
    if (contact == SoleContact::Centre) {
      lowest = std::min(lowest, centre.z());
      continue;
    }
    // Corners of the sole rectangle; the outer edge is on +y for the left foot.
    const double sign = side == BodySide::Left ? 1.0 : -1.0;
    const Matrix3d soleRot = tilt * sole.linear();
    for (double x : {dims::kSoleFront, -dims::kSoleBack})
      for (double y : {sign * dims::kSoleOuter, -sign * dims::kSoleInner})
        lowest = std::min(lowest, centre.z() + soleRot.row(2).dot(Vector3d(x, y, 0)));
  }
  return -lowest;
}

Isometry3d robotToTorso(const JointArray& joints, double roll, double pitch, SoleContact contact) {
  Isometry3d t = Isometry3d::Identity();
  t.linear() = torsoTilt(roll, pitch);
  t.translation() = Vector3d(0, 0, torsoHeightAboveGround(joints, roll, pitch, contact));
  return t;
}

}  // namespace nao
