#include "controllers/Kick.h"

#include <algorithm>
#include <cmath>

#include "controllers/Kinematics.h"
#include "robot/ForwardKinematics.h"
#include "robot/RobotDimensions.h"

namespace nao {

using Eigen::Isometry3d;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

constexpr double kGravity = 9.81;
constexpr double kBallRadius = 0.05;

double smooth5(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * s * (10 - 15 * s + 6 * s * s);
}

Isometry3d sole(const Vector3d& p, double yaw, double pitch = 0) {
  Isometry3d t = Isometry3d::Identity();
  t.linear() = rotZ(yaw) * rotY(pitch);
  t.translation() = p;
  return t;
}

}  // namespace

Vector2d Kick::ballTarget(bool leftFoot, const Params& p) {
  return {dims::kSoleFront + kBallRadius + p.ballGap, (leftFoot ? 1.0 : -1.0) * p.footSpacing / 2};
}

double Kick::duration() const {
  const Params& p = params_;
  return p.shiftTime + p.liftTime + p.strikeTime + p.holdTime + p.retractTime + p.lowerTime + p.returnTime;
}

void Kick::start(const SensorFrame& frame, const JointArray& stand, const Vector2d& ball, double direction) {
  stand_ = stand;
  startTime_ = frame.time;
  done_ = false;
  gyro_.setZero();
  leftShare_ = 0.5;
  // The stand frame: origin midway between the soles. Where the robot frame (below the torso) is in it.
  const Isometry3d l = torsoToSole(stand, BodySide::Left), r = torsoToSole(stand, BodySide::Right);
  const Vector3d mid = (l.translation() + r.translation()) / 2;
  torsoOffset_ = -mid.head<2>();
  torsoGuess_ = torsoOffset_;
  ballStart_ = ball + torsoOffset_;
  left_ = ballStart_.y() >= 0;
  const double s = left_ ? 1.0 : -1.0;
  const double half = params_.footSpacing / 2;
  // The strike: the toe through the ball's centre and followThrough beyond, the foot turned by
  // what the approach left of the direction.
  footYaw_ = std::clamp(direction + s * params_.yawBias, -params_.maxFootYaw, params_.maxFootYaw);
  const double reach = dims::kSoleFront + kBallRadius;
  const Vector2d contact = ballStart_ - reach * Vector2d(std::cos(footYaw_), std::sin(footYaw_));
  strikePoint_ = contact + params_.followThrough * Vector2d(std::cos(footYaw_), std::sin(footYaw_));
  strikePoint_.x() = std::clamp(strikePoint_.x(), 0.0, params_.strikeReach);
  strikePoint_.y() -= s * params_.strikeInward;
  strikePoint_.y() = s * std::clamp(s * strikePoint_.y(), half - 0.03, half + 0.05);
}

JointRequest Kick::update(const SensorFrame& frame) {
  const Params& p = params_;
  const double t = frame.time - startTime_;
  const double s = left_ ? 1.0 : -1.0;
  const double half = p.footSpacing / 2;
  const Vector3d standKick(0, s * half, 0), standSupport(0, -s * half, 0);
  const Vector2d support = standSupport.head<2>();
  const Vector2d comSupport = support + Vector2d(p.comForward, s * p.comInward);  // inward = towards the kicking side

  // Keyframes of the kicking sole and the COM.
  const double t1 = p.shiftTime, t2 = t1 + p.liftTime, t3 = t2 + p.strikeTime, t4 = t3 + p.holdTime,
               t5 = t4 + p.retractTime, t6 = t5 + p.lowerTime, t7 = t6 + p.returnTime;
  const Vector3d windUp(-p.windUp, strikePoint_.y(), p.liftHeight);
  const Vector3d strike(strikePoint_.x(), strikePoint_.y(), p.strikeHeight);
  const Vector3d retract(0, s * half, p.liftHeight);
  Vector3d kick = standKick;
  double yaw = 0, pitch = 0;
  Vector2d com = Vector2d::Zero();
  bool single = false;
  if (t < t1) {
    com = smooth5(t / p.shiftTime) * comSupport;
  } else if (t < t2) {
    const double a = smooth5((t - t1) / p.liftTime);
    kick = standKick + a * (windUp - standKick);
    yaw = a * footYaw_;
    pitch = a * p.windUpPitch;
    com = comSupport;
    single = true;
  } else if (t < t3) {
    const double a = std::clamp((t - t2) / p.strikeTime, 0.0, 1.0);
    kick = windUp + a * (strike - windUp);
    yaw = footYaw_;
    pitch = p.windUpPitch + a * (p.strikePitch - p.windUpPitch);
    com = comSupport;
    single = true;
  } else if (t < t4) {
    kick = strike;
    yaw = footYaw_;
    pitch = p.strikePitch;
    com = comSupport;
    single = true;
  } else if (t < t5) {
    const double a = smooth5((t - t4) / p.retractTime);
    kick = strike + a * (retract - strike);
    yaw = (1 - a) * footYaw_;
    pitch = (1 - a) * p.strikePitch;
    com = comSupport;
    single = true;
  } else if (t < t6) {
    const double a = smooth5((t - t5) / p.lowerTime);
    kick = retract + a * (standKick - retract);
    com = comSupport;
    single = a < 0.95;
  } else {
    com = (1 - smooth5((t - t6) / p.returnTime)) * comSupport;
    if (t >= t7) done_ = true;
  }

  JointRequest out;
  out.position = stand_;
  const Isometry3d kickSole = sole(kick, yaw, pitch), supportSole = sole(standSupport, 0);
  const Isometry3d torso = comIK(left_ ? kickSole : supportSole, left_ ? supportSole : kickSole, com, p.torsoHeight, 0, 0,
                                 out.position, torsoGuess_);
  torsoGuess_ = torso.translation().head<2>();

  // Sag compensation: the weight on each foot as the FSRs say, acting below the COM.
  const double fl = frame.fsr.total(true), fr = frame.fsr.total(false);
  if (fl + fr > 0.5) leftShare_ = 0.6 * leftShare_ + 0.4 * fl / (fl + fr);
  const Isometry3d inv = torso.inverse();
  const Vector3d force = inv.linear() * Vector3d(0, 0, totalMass() * kGravity);
  double hyp = 0;
  for (bool isLeft : {true, false}) {
    const double share = isLeft ? leftShare_ : 1 - leftShare_;
    const Isometry3d& solePose = (isLeft == left_) ? kickSole : supportSole;
    if (share < 0.05 || solePose.translation().z() > 0.005) continue;
    const Vector3d point = inv * Vector3d(com.x(), com.y(), 0);
    const Vector3d onSole = inv * solePose.translation();
    const Vector3d at(isLeft == left_ ? onSole.x() : point.x(), isLeft == left_ ? onSole.y() : point.y(), onSole.z());
    const auto tau = legJointTorques(out.position, isLeft ? BodySide::Left : BodySide::Right, at, share * force);
    const auto ids = legJointIds(isLeft ? BodySide::Left : BodySide::Right);
    hyp += tau[0];
    for (int i = 1; i < 6; ++i) out.position[ids[i]] += tau[i] / p.servoGain;
  }
  out.position[LHipYawPitch] += hyp / p.servoGain;

  // Gyro damping on the support ankle (both while both feet are down).
  gyro_ = 0.7 * gyro_ + 0.3 * frame.inertial.gyroscope.head<2>();
  for (bool isLeft : {true, false}) {
    if (single && isLeft == left_) continue;
    out.position[isLeft ? LAnklePitch : RAnklePitch] += p.gyroPitchGain * gyro_.y();
    out.position[isLeft ? LAnkleRoll : RAnkleRoll] += p.gyroRollGain * gyro_.x();
  }
  out.stiffness.fill(1.0);
  return out;
}

}  // namespace nao
