#include "perception/OwnBody.h"

#include <algorithm>
#include <limits>

#include "robot/ForwardKinematics.h"
#include "robot/RobotDimensions.h"

namespace nao {

using Eigen::Isometry3d;
using Eigen::Vector3d;

namespace {

// Squared distance of point p from the ray o + t d, t >= 0.
double pointRay2(const Vector3d& p, const Vector3d& o, const Vector3d& d) {
  const double t = std::max(0.0, (p - o).dot(d) / d.squaredNorm());
  return (o + t * d - p).squaredNorm();
}

// Squared distance of point p from the segment a b.
double pointSegment2(const Vector3d& p, const Vector3d& a, const Vector3d& b) {
  const Vector3d u = b - a;
  const double len2 = u.squaredNorm();
  const double s = len2 > 0 ? std::clamp((p - a).dot(u) / len2, 0.0, 1.0) : 0.0;
  return (a + s * u - p).squaredNorm();
}

}  // namespace

double raySegmentDistanceSquared(const Vector3d& o, const Vector3d& d, const Vector3d& a, const Vector3d& b) {
  // |a + s u - (o + t d)|^2 is convex in (s, t): its minimum over s in [0, 1], t >= 0 is the
  // free minimum where that is inside, else on one of the three edges.
  const Vector3d u = b - a, w = a - o;
  const double A = u.dot(u), B = u.dot(d), C = d.dot(d), D = u.dot(w), E = d.dot(w);
  const double denom = A * C - B * B;
  if (denom > 1e-12 * A * C) {
    const double s = (B * E - C * D) / denom, t = (A * E - B * D) / denom;
    if (s >= 0 && s <= 1 && t >= 0) return (w + s * u - t * d).squaredNorm();
  }
  return std::min({pointRay2(a, o, d), pointRay2(b, o, d), pointSegment2(o, a, b)});
}

bool rayMeetsBox(const Vector3d& o, const Vector3d& d, const OwnBody::Box& box) {
  // Slabs in the box's frame: the ray is inside all three on one interval of t >= 0.
  const Vector3d ob = box.pose.inverse() * o, db = box.pose.linear().transpose() * d;
  double tMin = 0, tMax = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    const double h = box.halfSize[i];
    if (std::abs(db[i]) < 1e-12) {
      if (std::abs(ob[i]) > h) return false;
      continue;
    }
    double t0 = (-h - ob[i]) / db[i], t1 = (h - ob[i]) / db[i];
    if (t0 > t1) std::swap(t0, t1);
    tMin = std::max(tMin, t0);
    tMax = std::min(tMax, t1);
    if (tMin > tMax) return false;
  }
  return true;
}

bool OwnBody::hides(const CameraMatrix& cm, const Eigen::Vector2d& pixel) const {
  const Vector3d o = cm.pose.translation(), d = cm.pixelRay(pixel);
  // A part the camera is inside of (a head pitched down onto a chest drawn too big) is left
  // out: it would hide the whole image.
  for (const Capsule& c : parts)
    if (pointSegment2(o, c.a, c.b) >= c.radius * c.radius && raySegmentDistanceSquared(o, d, c.a, c.b) < c.radius * c.radius)
      return true;
  for (const Box& b : boxes) {
    const Vector3d inBox = b.pose.inverse() * o;
    if ((inBox.cwiseAbs() - b.halfSize).maxCoeff() >= 0 && rayMeetsBox(o, d, b)) return true;
  }
  return false;
}

OwnBody ownBodyAt(const JointArray& joints, const Isometry3d& robotToTorso, const OwnBodyParams& p) {
  OwnBody body;
  auto add = [&](const Vector3d& aTorso, const Vector3d& bTorso, double r) {
    if (r > 0) body.parts.push_back({robotToTorso * aTorso, robotToTorso * bTorso, r});
  };
  auto addBox = [&](const Isometry3d& poseInTorso, const Vector3d& halfSize) {
    if (halfSize.minCoeff() > 0) body.boxes.push_back({robotToTorso * poseInTorso, halfSize});
  };
  Isometry3d torso = Isometry3d::Identity();
  torso.translation() = Vector3d(-0.005, 0, 0.115);
  addBox(torso, Vector3d(p.torsoHalfX, p.torsoHalfY, p.torsoHalfZ));
  for (BodySide side : {BodySide::Left, BodySide::Right}) {
    const bool left = side == BodySide::Left;
    const double sign = left ? 1.0 : -1.0;
    // Arm: the shoulder, the elbow (the ElbowYaw joint) and the hand point.
    const Vector3d shoulder(0, sign * dims::kShoulderY, dims::kShoulderZ);
    Isometry3d toUpperArm = Isometry3d::Identity();
    toUpperArm.translation() = shoulder;
    toUpperArm.linear() = rotY(joints[left ? LShoulderPitch : RShoulderPitch]) *
                          rotZ(joints[left ? LShoulderRoll : RShoulderRoll]);
    const Vector3d elbow = toUpperArm * Vector3d(dims::kUpperArmLength, sign * dims::kElbowOffsetY, 0);
    const Vector3d hand = torsoToHand(joints, side).translation();
    add(shoulder, shoulder, p.shoulder);
    add(shoulder, elbow, p.upperArm);
    add(elbow, hand, p.lowerArm);
    // Leg: the hip, the knee, the ankle and the foot.
    const Isometry3d ankle = torsoToAnkle(joints, side);
    const Vector3d hip(0, sign * dims::kHipY, 0);
    const Isometry3d sole = torsoToSole(joints, side);
    // The knee: kTibiaLength up the shin, whose direction is the ankle frame's z before the
    // ankle joints' own rotation (they turn only the foot).
    const Eigen::Matrix3d shinRot = ankle.linear() * (rotY(joints[left ? LAnklePitch : RAnklePitch]) *
                                                      rotX(joints[left ? LAnkleRoll : RAnkleRoll]))
                                                         .transpose();
    const Vector3d kneePoint = ankle.translation() + shinRot * Vector3d(0, 0, dims::kTibiaLength);
    add(hip, kneePoint, p.thigh);
    add(kneePoint, ankle.translation(), p.tibia);
    // Foot: the sole rectangle, footHeight high, footMargin bigger on every side.
    const double outer = sign * dims::kSoleOuter, inner = -sign * dims::kSoleInner;
    Isometry3d foot = sole;
    foot.translation() = sole * Vector3d((dims::kSoleFront - dims::kSoleBack) / 2, (outer + inner) / 2, p.footHeight / 2);
    addBox(foot, Vector3d((dims::kSoleFront + dims::kSoleBack) / 2 + p.footMargin,
                          (dims::kSoleOuter + dims::kSoleInner) / 2 + p.footMargin, p.footHeight / 2 + p.footMargin));
  }
  return body;
}

}  // namespace nao
