#include "controllers/Kinematics.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "robot/JointLimits.h"
#include "robot/RobotDimensions.h"

namespace nao {

using Eigen::Isometry3d;
using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180;

struct Limit {
  double min, max;
};

constexpr std::array<Limit, NumJoints> limitsInRadians() {
  std::array<Limit, NumJoints> out{};
  for (int j = 0; j < NumJoints; ++j) out[j] = {kJointLimitsDeg[j].min * kDeg, kJointLimitsDeg[j].max * kDeg};
  out[LHand] = out[RHand] = {0, 1};  // the opening, 0..1
  return out;
}
constexpr std::array<Limit, NumJoints> kLimits = limitsInRadians();

double sideSign(BodySide side) { return side == BodySide::Left ? 1.0 : -1.0; }

double wrap(double a) { return std::remainder(a, 2 * kPi); }

// Clamps each joint of a leg to its limits; false if any had to move.
bool clampLeg(LegJoints& leg, BodySide side) {
  const auto ids = legJointIds(side);
  double* v[6] = {&leg.hipYawPitch, &leg.hipRoll, &leg.hipPitch, &leg.knee, &leg.anklePitch, &leg.ankleRoll};
  bool ok = true;
  for (int i = 0; i < 6; ++i) {
    const double c = clampToLimits(ids[i], *v[i]);
    ok = ok && std::abs(c - *v[i]) < 1e-9;
    *v[i] = c;
  }
  return ok;
}

// The rotation of the HipYawPitch joint: about (0, 1, -s)/sqrt2 = Rx(-s pi/4) e_y.
Matrix3d hipYawPitchRotation(double angle, double s) {
  return rotX(-s * kPi / 4) * rotY(angle) * rotX(s * kPi / 4);
}

// Knee angle from the hip-ankle distance; false when the distance is out of the leg's range.
bool kneeFromDistance(double distance, double& knee) {
  const double l1 = dims::kThighLength, l2 = dims::kTibiaLength;
  const double c = (distance * distance - l1 * l1 - l2 * l2) / (2 * l1 * l2);
  knee = std::acos(std::clamp(c, -1.0, 1.0));
  return c <= 1.0 + 1e-12 && c >= -1.0;
}

}  // namespace

std::array<Joint, 6> legJointIds(BodySide side) {
  if (side == BodySide::Left) return {LHipYawPitch, LHipRoll, LHipPitch, LKneePitch, LAnklePitch, LAnkleRoll};
  return {LHipYawPitch, RHipRoll, RHipPitch, RKneePitch, RAnklePitch, RAnkleRoll};
}

void setLeg(JointArray& joints, BodySide side, const LegJoints& leg) {
  const auto ids = legJointIds(side);
  joints[ids[0]] = leg.hipYawPitch;
  joints[ids[1]] = leg.hipRoll;
  joints[ids[2]] = leg.hipPitch;
  joints[ids[3]] = leg.knee;
  joints[ids[4]] = leg.anklePitch;
  joints[ids[5]] = leg.ankleRoll;
}

LegJoints getLeg(const JointArray& joints, BodySide side) {
  const auto ids = legJointIds(side);
  return {joints[ids[0]], joints[ids[1]], joints[ids[2]], joints[ids[3]], joints[ids[4]], joints[ids[5]]};
}

double jointMin(Joint joint) { return kLimits[joint].min; }
double jointMax(Joint joint) { return kLimits[joint].max; }
double clampToLimits(Joint joint, double angle) { return std::clamp(angle, kLimits[joint].min, kLimits[joint].max); }

bool legIK(const Isometry3d& target, BodySide side, LegJoints& out) {
  const double s = sideSign(side);
  const double l1 = dims::kThighLength, l2 = dims::kTibiaLength;
  const Matrix3d rAnkle = target.linear();
  const Vector3d pAnkle = target.translation() + rAnkle.col(2) * dims::kFootHeight;
  const Vector3d hip(0, s * dims::kHipY, 0);
  // The hip seen from the ankle frame: knee, ankle roll and ankle pitch.
  const Vector3d d = rAnkle.transpose() * (hip - pAnkle);
  double knee = 0;
  bool ok = kneeFromDistance(d.norm(), knee);
  // Rx(roll) turns d into the foot's xz plane; of the two such rolls, the one within +-90 deg.
  double ankleRoll = std::atan2(d.y(), d.z());
  if (ankleRoll > kPi / 2) ankleRoll -= kPi;
  if (ankleRoll < -kPi / 2) ankleRoll += kPi;
  const double phiU = std::atan2(d.x(), std::sin(ankleRoll) * d.y() + std::cos(ankleRoll) * d.z());
  const double phiV = std::atan2(-l1 * std::sin(knee), l1 * std::cos(knee) + l2);
  const double anklePitch = phiV - phiU;
  // The hip's rotation, seen in the frame turned by s pi/4 about x: Ry(hyp) Rx(roll + s pi/4) Ry(pitch).
  const Matrix3d rHip = rAnkle * rotX(-ankleRoll) * rotY(-anklePitch - knee);
  const Matrix3d m = rotX(s * kPi / 4) * rHip;
  const double rollShifted = s * std::acos(std::clamp(m(1, 1), -1.0, 1.0));
  out.hipYawPitch = std::atan2(s * m(0, 1), s * m(2, 1));
  out.hipRoll = rollShifted - s * kPi / 4;
  out.hipPitch = std::atan2(s * m(1, 0), -s * m(1, 2));
  out.knee = knee;
  out.anklePitch = wrap(anklePitch);
  out.ankleRoll = ankleRoll;
  ok = clampLeg(out, side) && ok;
  return ok;
}

bool legIKFixedHipYawPitch(const Isometry3d& target, BodySide side, double hipYawPitch, LegJoints& out) {
  const double s = sideSign(side);
  const double l1 = dims::kThighLength, l2 = dims::kTibiaLength;
  const Matrix3d rAnkle = target.linear();
  const Vector3d pAnkle = target.translation() + rAnkle.col(2) * dims::kFootHeight;
  const Vector3d hip(0, s * dims::kHipY, 0);
  const Matrix3d r0 = hipYawPitchRotation(hipYawPitch, s);
  // The ankle in the frame after HipYawPitch: Rx(roll) Ry(pitch) [thigh, knee, tibia].
  const Vector3d w = r0.transpose() * (pAnkle - hip);
  const double hipRoll = std::atan2(w.y(), -w.z());
  const double lz = -std::hypot(w.y(), w.z());  // the leg plane's downward component
  double knee = 0;
  bool ok = kneeFromDistance(std::hypot(w.x(), lz), knee);
  // In the leg plane: Ry(pitch) (-l2 sin k, -(l1 + l2 cos k)) = (w.x, lz); Ry adds to atan2(x, z).
  const double hipPitch = wrap(std::atan2(w.x(), lz) - std::atan2(-l2 * std::sin(knee), -(l1 + l2 * std::cos(knee))));
  // Ankle: match the sole normal in the shin frame.
  const Matrix3d shin = r0 * rotX(hipRoll) * rotY(hipPitch + knee);
  const Vector3d n = shin.transpose() * rAnkle.col(2);
  out.hipYawPitch = hipYawPitch;
  out.hipRoll = hipRoll;
  out.hipPitch = hipPitch;
  out.knee = knee;
  out.ankleRoll = -std::asin(std::clamp(n.y(), -1.0, 1.0));
  out.anklePitch = std::atan2(n.x(), n.z());
  ok = clampLeg(out, side) && ok;
  return ok;
}

bool legsIK(const Isometry3d& left, const Isometry3d& right, JointArray& joints, double ratio) {
  LegJoints l, r;
  legIK(left, BodySide::Left, l);
  legIK(right, BodySide::Right, r);
  ratio = std::clamp(ratio, 0.0, 1.0);
  const double hyp = clampToLimits(LHipYawPitch, ratio * l.hipYawPitch + (1 - ratio) * r.hipYawPitch);
  const bool okLeft = legIKFixedHipYawPitch(left, BodySide::Left, hyp, l);
  const bool okRight = legIKFixedHipYawPitch(right, BodySide::Right, hyp, r);
  setLeg(joints, BodySide::Left, l);
  setLeg(joints, BodySide::Right, r);
  return okLeft && okRight;
}

std::array<double, 6> legJointTorques(const JointArray& joints, BodySide side, const Vector3d& point,
                                      const Vector3d& force) {
  const double s = sideSign(side);
  const LegJoints l = getLeg(joints, side);
  const Vector3d hip(0, s * dims::kHipY, 0);
  const Matrix3d r0 = hipYawPitchRotation(l.hipYawPitch, s);
  const Matrix3d rRoll = r0 * rotX(l.hipRoll);
  const Matrix3d rThigh = rRoll * rotY(l.hipPitch);
  const Matrix3d rShin = rThigh * rotY(l.knee);
  const Matrix3d rAnkle = rShin * rotY(l.anklePitch);
  const Vector3d knee = hip + rThigh * Vector3d(0, 0, -dims::kThighLength);
  const Vector3d ankle = knee + rShin * Vector3d(0, 0, -dims::kTibiaLength);
  const std::array<std::pair<Vector3d, Vector3d>, 6> axes = {{
      {hip, r0 * Vector3d(0, 1, -s).normalized()},
      {hip, rRoll.col(0)},
      {hip, rThigh.col(1)},
      {knee, rShin.col(1)},
      {ankle, rAnkle.col(1)},
      {ankle, rAnkle.col(0)},
  }};
  std::array<double, 6> tau{};
  for (int i = 0; i < 6; ++i) tau[i] = -axes[i].second.dot((point - axes[i].first).cross(force));
  return tau;
}

Isometry3d comIK(const Isometry3d& leftSole, const Isometry3d& rightSole, const Eigen::Vector2d& com, double torsoHeight,
                 double torsoPitch, double torsoYaw, JointArray& joints, const Eigen::Vector2d& torsoGuess) {
  Eigen::Vector2d xy = torsoGuess;
  Isometry3d torso = Isometry3d::Identity();
  torso.linear() = rotZ(torsoYaw) * rotY(torsoPitch);
  for (int iter = 0; iter < 4; ++iter) {
    torso.translation() = Vector3d(xy.x(), xy.y(), torsoHeight);
    const Isometry3d inv = torso.inverse();
    legsIK(inv * leftSole, inv * rightSole, joints);
    if (iter == 3) break;
    xy += com - (torso * centerOfMass(joints)).head<2>();
  }
  return torso;
}

void setArm(JointArray& joints, BodySide side, const ArmJoints& arm) {
  const bool left = side == BodySide::Left;
  joints[left ? LShoulderPitch : RShoulderPitch] = arm.shoulderPitch;
  joints[left ? LShoulderRoll : RShoulderRoll] = arm.shoulderRoll;
  joints[left ? LElbowYaw : RElbowYaw] = arm.elbowYaw;
  joints[left ? LElbowRoll : RElbowRoll] = arm.elbowRoll;
  joints[left ? LWristYaw : RWristYaw] = arm.wristYaw;
}

ArmJoints getArm(const JointArray& joints, BodySide side) {
  const bool left = side == BodySide::Left;
  return {joints[left ? LShoulderPitch : RShoulderPitch], joints[left ? LShoulderRoll : RShoulderRoll],
          joints[left ? LElbowYaw : RElbowYaw], joints[left ? LElbowRoll : RElbowRoll],
          joints[left ? LWristYaw : RWristYaw]};
}

bool armIK(const Vector3d& hand, BodySide side, double elbowYaw, double wristYaw, ArmJoints& out) {
  const bool left = side == BodySide::Left;
  const double s = sideSign(side);
  const Joint rollId = left ? LShoulderRoll : RShoulderRoll;
  const Joint elbowId = left ? LElbowRoll : RElbowRoll;
  const Joint pitchId = left ? LShoulderPitch : RShoulderPitch;
  const Vector3d shoulder(0, s * dims::kShoulderY, dims::kShoulderZ);
  const Vector3d w = hand - shoulder;
  // Upper arm e (bicep frame) and forearm + hand f (forearm frame).
  const Vector3d e(dims::kUpperArmLength, s * dims::kElbowOffsetY, 0);
  const Vector3d f = Vector3d(dims::kLowerArmLength, 0, 0) + rotX(wristYaw) * Vector3d(dims::kHandOffsetX, 0, dims::kHandOffsetZ);
  // |e + Rx(ey) Rz(er) f|^2 = |w|^2 is A cos er + B sin er = rhs.
  const Vector3d g = rotX(elbowYaw).transpose() * e;  // e . Rx(ey) v = (Rx(ey)^T e) . v
  const double a = g.x() * f.x() + g.y() * f.y();
  const double b = g.y() * f.x() - g.x() * f.y();
  const double c = g.z() * f.z();
  const double rhs = (w.squaredNorm() - e.squaredNorm() - f.squaredNorm()) / 2 - c;
  const double amp = std::hypot(a, b);
  bool ok = std::abs(rhs) <= amp;
  const double delta = std::atan2(b, a);
  const double spread = std::acos(std::clamp(rhs / amp, -1.0, 1.0));
  // Two elbow solutions; the one within (or nearest to) the joint's range.
  double elbowRoll = 0, best = 1e9;
  for (double cand : {wrap(delta + spread), wrap(delta - spread)}) {
    const double dist = std::abs(clampToLimits(elbowId, cand) - cand);
    if (dist < best) best = dist, elbowRoll = cand;
  }
  ok = ok && best < 1e-9;
  elbowRoll = clampToLimits(elbowId, elbowRoll);
  const Vector3d u = e + rotX(elbowYaw) * rotZ(elbowRoll) * f;
  // ShoulderRoll turns u's y component to w's (ShoulderPitch keeps y).
  const double ru = std::hypot(u.x(), u.y());
  const double phi = std::atan2(u.y(), u.x());
  const double sn = std::clamp(w.y() / ru, -1.0, 1.0);
  ok = ok && std::abs(w.y()) <= ru;
  double shoulderRoll = 0;
  best = 1e9;
  for (double cand : {wrap(std::asin(sn) - phi), wrap(kPi - std::asin(sn) - phi)}) {
    const double dist = std::abs(clampToLimits(rollId, cand) - cand);
    if (dist < best) best = dist, shoulderRoll = cand;
  }
  ok = ok && best < 1e-9;
  shoulderRoll = clampToLimits(rollId, shoulderRoll);
  const Vector3d v = rotZ(shoulderRoll) * u;
  const double shoulderPitch = wrap(std::atan2(w.x(), w.z()) - std::atan2(v.x(), v.z()));
  out.shoulderPitch = clampToLimits(pitchId, shoulderPitch);
  ok = ok && std::abs(out.shoulderPitch - shoulderPitch) < 1e-9;
  out.shoulderRoll = shoulderRoll;
  out.elbowYaw = elbowYaw;
  out.elbowRoll = elbowRoll;
  out.wristYaw = wristYaw;
  return ok;
}

namespace {

struct Link {
  double mass;
  Vector3d com;  // left side; y mirrored for the right
};

// nao-v6.md: masses (kg) and COMs (m) in each link's joint frame.
const Link kTorso{1.0496, {-0.00413, 0, 0.12842}};
const Link kNeck{0.07842, {0, 0, -0.02742}};
const Link kHead{0.6594, {0.00109, 0.00146, 0.05719}};
const Link kShoulder{0.09304, {-0.00165, -0.02663, 0.00014}};
const Link kBicep{0.15777, {0.02455, 0.00563, 0.0033}};
const Link kElbow{0.06483, {-0.02744, 0, -0.00014}};
const Link kForearm{0.07761, {0.02556, 0.00281, 0.00076}};
const Link kHand{0.18533, {0.03434, -0.00088, 0.00308}};
const Link kPelvis{0.06981, {-0.00781, -0.01114, 0.02661}};
const Link kHip{0.14053, {-0.01549, 0.00029, -0.00515}};
const Link kThigh{0.38968, {0.00138, 0.00221, -0.05373}};
const Link kTibia{0.30142, {0.00453, 0.00225, -0.04936}};
const Link kAnkle{0.13416, {0.00045, 0.00029, 0.00685}};
const Link kFoot{0.17184, {0.02542, 0.0033, -0.03239}};

Vector3d mirrored(const Vector3d& v, double s) { return {v.x(), s * v.y(), v.z()}; }

Isometry3d trans(double x, double y, double z) {
  Isometry3d t = Isometry3d::Identity();
  t.translation() = Vector3d(x, y, z);
  return t;
}
Isometry3d rot(const Matrix3d& r) {
  Isometry3d t = Isometry3d::Identity();
  t.linear() = r;
  return t;
}

}  // namespace

double totalMass() {
  double m = kTorso.mass + kNeck.mass + kHead.mass;
  for (const Link* l : {&kShoulder, &kBicep, &kElbow, &kForearm, &kHand, &kPelvis, &kHip, &kThigh, &kTibia, &kAnkle, &kFoot})
    m += 2 * l->mass;
  return m;
}

Vector3d centerOfMass(const JointArray& j) {
  Vector3d sum = kTorso.mass * kTorso.com;
  const auto add = [&](const Isometry3d& frame, const Link& link, double s) { sum += link.mass * (frame * mirrored(link.com, s)); };
  Isometry3d t = trans(0, 0, dims::kNeckZ) * rot(rotZ(j[HeadYaw]));
  add(t, kNeck, 1);
  add(t * rot(rotY(j[HeadPitch])), kHead, 1);
  for (BodySide side : {BodySide::Left, BodySide::Right}) {
    const double s = sideSign(side);
    const ArmJoints a = getArm(j, side);
    t = trans(0, s * dims::kShoulderY, dims::kShoulderZ) * rot(rotY(a.shoulderPitch));
    add(t, kShoulder, s);
    t = t * rot(rotZ(a.shoulderRoll));
    add(t, kBicep, s);
    t = t * trans(dims::kUpperArmLength, s * dims::kElbowOffsetY, 0) * rot(rotX(a.elbowYaw));
    add(t, kElbow, s);
    t = t * rot(rotZ(a.elbowRoll));
    add(t, kForearm, s);
    t = t * trans(dims::kLowerArmLength, 0, 0) * rot(rotX(a.wristYaw));
    add(t, kHand, s);

    const LegJoints l = getLeg(j, side);
    t = trans(0, s * dims::kHipY, 0) * rot(hipYawPitchRotation(l.hipYawPitch, s));
    add(t, kPelvis, s);
    t = t * rot(rotX(l.hipRoll));
    add(t, kHip, s);
    t = t * rot(rotY(l.hipPitch));
    add(t, kThigh, s);
    t = t * trans(0, 0, -dims::kThighLength) * rot(rotY(l.knee));
    add(t, kTibia, s);
    t = t * trans(0, 0, -dims::kTibiaLength) * rot(rotY(l.anklePitch));
    add(t, kAnkle, s);
    t = t * rot(rotX(l.ankleRoll));
    add(t, kFoot, s);
  }
  return sum / totalMass();
}

}  // namespace nao
