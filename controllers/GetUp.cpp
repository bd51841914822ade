#include "controllers/GetUp.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <utility>

#include "controllers/Kinematics.h"
#include "robot/ForwardKinematics.h"
#include "robot/RobotDimensions.h"

namespace nao {

namespace {

constexpr double kDeg = M_PI / 180;

double smoothstep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

// A symmetric frame from the angles (deg) that matter; left values, the right side mirrored.
struct Pose {
  double headPitch = 0;
  double shoulderPitch = 90, shoulderRoll = 10, elbowYaw = -90, elbowRoll = -5, wristYaw = 0;
  double hipYawPitch = 0, hipRoll = 0, hipPitch = 0, knee = 0, anklePitch = 0, ankleRoll = 0;
};

GetUp::KeyFrame frame(double duration, double stiffness, const Pose& p) {
  GetUp::KeyFrame k;
  k.duration = duration;
  k.stiffness = stiffness;
  JointArray& j = k.angles;
  j[HeadYaw] = 0;
  j[HeadPitch] = p.headPitch * kDeg;
  j[LShoulderPitch] = j[RShoulderPitch] = p.shoulderPitch * kDeg;
  j[LShoulderRoll] = p.shoulderRoll * kDeg;
  j[RShoulderRoll] = -p.shoulderRoll * kDeg;
  j[LElbowYaw] = p.elbowYaw * kDeg;
  j[RElbowYaw] = -p.elbowYaw * kDeg;
  j[LElbowRoll] = p.elbowRoll * kDeg;
  j[RElbowRoll] = -p.elbowRoll * kDeg;
  j[LWristYaw] = p.wristYaw * kDeg;
  j[RWristYaw] = -p.wristYaw * kDeg;
  j[LHipYawPitch] = p.hipYawPitch * kDeg;
  j[LHipRoll] = p.hipRoll * kDeg;
  j[RHipRoll] = -p.hipRoll * kDeg;
  j[LHipPitch] = j[RHipPitch] = p.hipPitch * kDeg;
  j[LKneePitch] = j[RKneePitch] = p.knee * kDeg;
  j[LAnklePitch] = j[RAnklePitch] = p.anklePitch * kDeg;
  j[LAnkleRoll] = p.ankleRoll * kDeg;
  j[RAnkleRoll] = -p.ankleRoll * kDeg;
  for (int i = 0; i < NumJoints; ++i) j[i] = clampToLimits(static_cast<Joint>(i), j[i]);
  return k;
}

Pose squat() {
  Pose p;
  p.hipPitch = -88;
  p.knee = 120;
  p.anklePitch = -46;
  p.shoulderPitch = 70;
  return p;
}

}  // namespace

JointArray GetUp::squatPosture() { return frame(1, 1, squat()).angles; }

double GetUp::squatHeight() {
  const Eigen::Isometry3d sole = torsoToSole(squatPosture(), BodySide::Left);
  return (sole.linear().transpose() * -sole.translation()).z();
}

double GetUp::squatTorsoPitch() {
  const Eigen::Matrix3d r = torsoToSole(squatPosture(), BodySide::Left).linear().transpose();
  return std::atan2(-r(2, 0), r(2, 2));
}

std::vector<GetUp::KeyFrame> GetUp::frontFrames() {
  Pose a;  // arms forward above the head, head up, legs straight
  a.headPitch = -30;
  a.shoulderPitch = -60;
  a.shoulderRoll = 30;
  a.elbowRoll = -40;
  Pose b = a;  // pike: hips up on straight legs
  b.hipPitch = -88;
  b.anklePitch = 40;
  Pose c = b;  // arms push the chest up
  c.shoulderPitch = 20;
  c.elbowRoll = -5;
  Pose d = c;  // knees in: feet under the hips
  d.knee = 120;
  d.anklePitch = -50;
  Pose e = squat();
  return {frame(0.5, 1, a), frame(0.8, 1, b), frame(0.6, 1, c), frame(0.8, 1, d), frame(0.8, 1, e)};
}

std::vector<GetUp::KeyFrame> GetUp::backFrames() {
  Pose a;  // knees up, feet planted, arms back under the body
  a.headPitch = 20;
  a.shoulderPitch = 120;
  a.elbowYaw = 20;
  a.elbowRoll = -85;
  a.wristYaw = -90;
  a.knee = 90;
  Pose b = a;  // bridge
  b.hipPitch = 30;
  Pose c = b;  // arms straight: the torso is lifted
  c.elbowRoll = -5;
  Pose d = c;  // sit up
  d.hipPitch = -60;
  d.knee = 60;
  Pose e = squat();
  return {frame(0.5, 1, a), frame(0.6, 1, b), frame(0.6, 1, c), frame(0.8, 1, d), frame(0.8, 1, e)};
}

std::vector<GetUp::KeyFrame> GetUp::sideRollFrames(bool lyingOnLeft) {
  // Onto the back: the upper arm swings over the body, the upper leg bends across.
  Pose p;
  p.shoulderPitch = 0;
  p.shoulderRoll = 0;
  GetUp::KeyFrame k = frame(0.6, 1, p);
  if (lyingOnLeft) {
    k.angles[RShoulderPitch] = -0.5;
    k.angles[RHipPitch] = -0.8;
    k.angles[RKneePitch] = 1.2;
  } else {
    k.angles[LShoulderPitch] = -0.5;
    k.angles[LHipPitch] = -0.8;
    k.angles[LKneePitch] = 1.2;
  }
  return {k, frame(0.6, 0.6, Pose{})};
}

void GetUp::setFrames(FallDirection lying, const std::vector<KeyFrame>& frames) {
  (lying == FallDirection::Back ? customBack_ : customFront_) = frames;
}

void GetUp::startFrames(const SensorFrame& frame, const std::vector<KeyFrame>& frames) {
  frames_ = frames;
  frame_ = 0;
  frameStart_ = frame.time;
  from_ = frame.joints.position;
}

void GetUp::start(const SensorFrame& frame, FallDirection lying, const JointArray& stand) {
  stand_ = stand;
  done_ = false;
  failed_ = false;
  rising_ = false;
  gyro_.setZero();
  rollingFirst_ = lying == FallDirection::Left || lying == FallDirection::Right;
  if (rollingFirst_) {
    startFrames(frame, sideRollFrames(lying == FallDirection::Left));
  } else if (lying == FallDirection::Back) {
    startFrames(frame, customBack_.empty() ? backFrames() : customBack_);
  } else {
    startFrames(frame, customFront_.empty() ? frontFrames() : customFront_);
  }
}

JointRequest GetUp::update(const SensorFrame& frame) {
  JointRequest out;
  out.stiffness.fill(1.0);
  if (done_ || failed_) {
    out.position = frame.joints.position;
    return out;
  }
  if (!rising_) {
    const KeyFrame& k = frames_[frame_];
    const double s = smoothstep((frame.time - frameStart_) / k.duration);
    for (int j = 0; j < NumJoints; ++j) out.position[j] = from_[j] + s * (k.angles[j] - from_[j]);
    out.stiffness.fill(k.stiffness);
    if (frame.time - frameStart_ >= k.duration) {
      from_ = k.angles;
      frameStart_ = frame.time;
      if (++frame_ >= frames_.size()) {
        if (rollingFirst_) {
          // On the back now (or on the front: the IMU says which); the real get-up follows.
          rollingFirst_ = false;
          const bool back = frame.inertial.angle.y() < 0;
          startFrames(frame, back ? (customBack_.empty() ? backFrames() : customBack_)
                                  : (customFront_.empty() ? frontFrames() : customFront_));
          return out;
        }
        // In the squat: upright enough to rise?
        const double tilt = std::acos(std::clamp(std::cos(frame.inertial.angle.x()) * std::cos(frame.inertial.angle.y()), -1.0, 1.0));
        if (tilt > params_.squatMaxTilt + std::abs(squatTorsoPitch())) {
          failed_ = true;
          return out;
        }
        rising_ = true;
        riseStart_ = frame.time;
        riseFrom_ = out.position;
      }
    }
    return out;
  }
  // Rising: feet flat, the COM above their midpoint, the torso from the squat's height and
  // pitch to the stand's.
  const double s = smoothstep((frame.time - riseStart_) / params_.riseTime);
  const JointArray squatJ = riseFrom_;
  const double h0 = squatHeight(), p0 = squatTorsoPitch();
  out.position = stand_;
  Eigen::Isometry3d l = Eigen::Isometry3d::Identity(), r = Eigen::Isometry3d::Identity();
  l.translation() = Eigen::Vector3d(0, params_.footSpacing / 2, 0);
  r.translation() = Eigen::Vector3d(0, -params_.footSpacing / 2, 0);
  comIK(l, r, Eigen::Vector2d(0.005, 0), h0 + s * (params_.torsoHeight - h0), (1 - s) * p0, 0, out.position);
  // Arms and head from the squat's to the stand's.
  for (int j : {HeadYaw, HeadPitch, LShoulderPitch, LShoulderRoll, LElbowYaw, LElbowRoll, LWristYaw, RShoulderPitch,
                RShoulderRoll, RElbowYaw, RElbowRoll, RWristYaw})
    out.position[j] = squatJ[j] + s * (stand_[j] - squatJ[j]);
  gyro_ = 0.7 * gyro_ + 0.3 * frame.inertial.gyroscope.head<2>();
  for (Joint a : {LAnklePitch, RAnklePitch}) out.position[a] += params_.gyroGain * gyro_.y();
  for (Joint a : {LAnkleRoll, RAnkleRoll}) out.position[a] += params_.gyroGain * gyro_.x();
  if (s >= 1) done_ = true;
  return out;
}

}  // namespace nao
