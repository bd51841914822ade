#include "controllers/Walk.h"

#include <algorithm>
#include <cmath>

#include "controllers/InertialOdometry.h"
#include "controllers/Kinematics.h"
#include "controllers/StandController.h"
#include "robot/ForwardKinematics.h"
#include "robot/RobotDimensions.h"

namespace nao {

NAO_DEBUG_CHANNEL(kWalkTrace, "walk_trace",
                  "each step at mid-swing: the swing target in the support foot's frame (m, deg) as planned "
                  "(nominal), moved by the DCM (adjusted) and clipped, and the applied speed (m/s, deg/s)");

using Eigen::Isometry3d;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

constexpr double kGravity = 9.81;
constexpr double kNominalCycle = 0.012;
constexpr int kPreviewSteps = 4;

double smooth5(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * s * (10 - 15 * s + 6 * s * s);
}

Isometry3d footIsometry(const Pose2& p, double z) {
  Isometry3d t = Isometry3d::Identity();
  t.linear() = rotZ(p.theta);
  t.translation() = Vector3d(p.x, p.y, z);
  return t;
}

double towards(double value, double target, double maxDelta) {
  return value + std::clamp(target - value, -maxDelta, maxDelta);
}

double meanAngle(double a, double b) { return Pose2::wrap(a + Pose2::wrap(b - a) / 2); }

// The rotation about `v` by |v| (a rotation vector).
Eigen::Matrix3d rotationOf(const Vector3d& v) {
  const double angle = v.norm();
  return Eigen::AngleAxisd(angle, angle > 1e-12 ? Vector3d(v / angle) : Vector3d::UnitZ()).toRotationMatrix();
}

// The rate of the torso's yaw (ZYX Euler angles, the robot frame's heading) from the body
// rates: psi' = (q sin(roll) + r cos(roll)) / cos(pitch). Not the vertical component of the
// angular velocity: with the torso rocking in roll and pitch each step, that one accumulates a
// drift (the rocking's enclosed area) the heading does not have.
double yawRateOf(const SensorFrame& frame) {
  const double roll = frame.inertial.angle.x(), pitch = frame.inertial.angle.y();
  const Eigen::Vector3d& w = frame.inertial.gyroscope;
  return (w.y() * std::sin(roll) + w.z() * std::cos(roll)) / std::cos(pitch);
}

// The robot frame seen from a point of a sole (sole frame coordinates), on the ground plane:
// its position from that point, turned into the sole's heading, and its heading relative to
// the sole. `sole` is the sole in the torso's yaw-free frame.
Pose2 robotInSole(const Isometry3d& sole, const Vector3d& point) {
  const Vector3d toTorso = -(sole * point);
  const Vector3d soleX = sole.linear().col(0);
  const double soleYaw = std::atan2(soleX.y(), soleX.x());
  const Vector2d v = rotZ(-soleYaw).topLeftCorner<2, 2>() * toTorso.head<2>();
  return Pose2(v.x(), v.y(), -soleYaw);
}

// Where a foot touches the ground, in its sole frame, from its four FSRs: their centre of
// pressure, moved out to the sole's edge when all the weight is on the sensors along one edge
// (the foot is on its toes, its heel or a side; the sensors sit 2-3 cm inside the sole's
// outline). The sole frame's origin when the foot carries next to nothing.
Vector3d groundContact(const SensorFrame& frame, bool left) {
  const int first = left ? 0 : 4;
  double total = 0;
  for (int i = first; i < first + 4; ++i) total += std::max(0.0, frame.fsr.weight[i]);
  if (total < 0.05) return Vector3d::Zero();
  const auto w = [&](int k) { return std::max(0.0, frame.fsr.weight[first + k]) / total; };
  const double front = w(0) + w(1);     // share on the front sensors
  const double leftSide = w(0) + w(2);  // share on the sensors on the foot's left
  // Bilinear in the sensors' rectangle (x0 rear .. x1 front, y0 right .. y1 left) ...
  const double x1 = dims::fsrX(first), x0 = dims::fsrX(first + 2);
  const double y1 = dims::fsrY(first), y0 = dims::fsrY(first + 1);
  const double yLeftEdge = left ? dims::kSoleOuter : dims::kSoleInner, yRightEdge = left ? -dims::kSoleInner : -dims::kSoleOuter;
  // ... and beyond it towards the edge once one side carries (nearly) everything.
  const auto spread = [](double share, double lo, double hi, double edgeLo, double edgeHi) {
    constexpr double kEdge = 0.95;
    if (share > kEdge) return hi + (share - kEdge) / (1 - kEdge) * (edgeHi - hi);
    if (share < 1 - kEdge) return lo - (1 - kEdge - share) / (1 - kEdge) * (lo - edgeLo);
    return lo + share * (hi - lo);
  };
  return Vector3d(spread(front, x0, x1, -dims::kSoleBack, dims::kSoleFront), spread(leftSide, y0, y1, yRightEdge, yLeftEdge), 0);
}

}  // namespace

Walk::Walk(const Params& params) : params_(params), inertial_(params.inertial) {
  const JointArray stand = standPosture();
  {
    const Isometry3d l = torsoToSole(stand, BodySide::Left), r = torsoToSole(stand, BodySide::Right);
    const Vector3d mid = (l.translation() + r.translation()) / 2;
    standOffset_ = Pose2(-mid.x(), -mid.y(), 0);
  }
  arms_ = stand;
  comHeight_ = params_.torsoHeight + centerOfMass(stand).z();
  omega_ = std::sqrt(kGravity / comHeight_);
  lastCommand_ = stand;
}

JointArray Walk::standPosture() const {
  JointArray joints = StandController::standPosture();
  joints[LShoulderRoll] = 0.15;
  joints[RShoulderRoll] = -0.15;
  // Feet under the hips at footSpacing; the torso shifted so that the COM is above their midpoint.
  Vector2d torso = Vector2d::Zero();
  for (int i = 0; i < 8; ++i) {
    Isometry3d t = Isometry3d::Identity();
    t.translation() = Vector3d(torso.x(), torso.y(), params_.torsoHeight);
    t.linear() = rotY(params_.torsoPitch);
    const Isometry3d inv = t.inverse();
    legsIK(inv * footIsometry({0, params_.footSpacing / 2, 0}, 0), inv * footIsometry({0, -params_.footSpacing / 2, 0}, 0), joints);
    const Vector3d com = t * centerOfMass(joints);
    torso -= com.head<2>();
  }
  return joints;
}

Pose2 Walk::clipSpeed(const Pose2& s) const {
  Pose2 out;
  out.x = std::clamp(s.x, -params_.maxBackward, params_.maxForward);
  out.y = std::clamp(s.y, -params_.maxSide, params_.maxSide);
  out.theta = std::clamp(s.theta, -params_.maxTurn, params_.maxTurn);
  // Combined speeds share the step: keep (x, y, theta) inside the ellipsoid of the limits.
  const double ex = out.x / (out.x >= 0 ? params_.maxForward : params_.maxBackward);
  const double ey = out.y / params_.maxSide, et = out.theta / params_.maxTurn;
  const double n = std::sqrt(ex * ex + ey * ey + et * et);
  if (n > 1) out = {out.x / n, out.y / n, out.theta / n};
  return out;
}

void Walk::reset(const SensorFrame& frame) {
  phase_ = Phase::Standing;
  left_ = {0, params_.footSpacing / 2, 0};
  right_ = {0, -params_.footSpacing / 2, 0};
  support_ = right_;
  c_ = Vector2d::Zero();
  cd_ = Vector2d::Zero();
  zmp_ = Vector2d::Zero();
  torsoXY_ = Vector2d::Zero();
  speed_ = {};
  t_ = 0;
  lastTime_ = frame.time;
  haveRelative_ = false;
  haveMeasurement_ = false;
  havePreviousIK_ = false;
  gyroFiltered_.setZero();
  stopRequested_ = false;
  yawError_ = 0;
  headingCorrection_ = 0;
}

Vector2d Walk::zmpOf(const Pose2& foot, bool left) const {
  return foot * Vector2d(params_.zmpX, left ? -params_.zmpYInside : params_.zmpYInside);
}

// Where the swing foot lands for a speed: the feet's midpoint moves by the step's share of the
// speed; sideways and turning steps open with the foot on that side and close with the other.
Pose2 Walk::nominalTarget(const Pose2& support, bool swingLeft, const Pose2& speed) const {
  const double w = swingLeft ? 1.0 : -1.0;
  const double T = params_.stepDuration;
  const Pose2 mid = support * Pose2(0, w * params_.footSpacing / 2, 0);
  const double dx = speed.x * T;
  const double dy = speed.y * w > 0 ? 2 * speed.y * T : 0.0;
  const double dtheta = speed.theta * w > 0 ? 2 * speed.theta * T : 0.0;
  const Pose2 target = mid * Pose2(0, 0, dtheta) * Pose2(dx, dy, 0) * Pose2(0, w * params_.footSpacing / 2, 0);
  return clipTarget(support, swingLeft, target);
}

Pose2 Walk::clipTarget(const Pose2& support, bool swingLeft, const Pose2& target) const {
  const double w = swingLeft ? 1.0 : -1.0;
  Pose2 rel = support.inverse() * target;
  rel.x = std::clamp(rel.x, -params_.maxStepBackward, params_.maxStepForward);
  const double lateral = std::clamp(w * rel.y, params_.footSpacing - params_.maxStepInward,
                                    params_.footSpacing + params_.maxStepOutward);
  rel.y = w * lateral;
  // Toes may open (swing foot turned outwards) more than they close.
  rel.theta = w * std::clamp(w * rel.theta, -0.25, 0.8);
  return support * rel;
}

// The ZMP of a step moves through the support sole from heel to toe (or across it) with the
// COM, which travels over the sole by half the distance between the feet before and after:
// less horizontal force is needed, the gait is smoother at speed.
Walk::StepZmp Walk::stepZmp(const Pose2& support, bool supportLeft, const Pose2& from, const Pose2& to) const {
  const Vector2d ref = zmpOf(support, supportLeft);
  const Vector2d travel = (to.translation() - from.translation()) / 2;
  const double c = std::cos(support.theta), s = std::sin(support.theta);
  Vector2d local(c * travel.x() + s * travel.y(), -s * travel.x() + c * travel.y());
  local.x() = std::clamp(params_.zmpTravelX * local.x(), -params_.maxZmpTravelX, params_.maxZmpTravelX);
  local.y() = std::clamp(params_.zmpTravelY * local.y(), -params_.maxZmpTravelY, params_.maxZmpTravelY);
  const Vector2d w(c * local.x() - s * local.y(), s * local.x() + c * local.y());
  return {ref - w / 2, ref + w / 2};
}

Vector2d Walk::zmpAt(const StepZmp& z, double t) const {
  return z.p0 + std::clamp(t / params_.stepDuration, 0.0, 1.0) * (z.p1 - z.p0);
}

// DCM with a ZMP moving at a constant rate pd: xi(t) = p(t) + pd/omega + (xi0 - p0 - pd/omega) e^(omega t).
Vector2d Walk::dcmAtStart(const StepZmp& z, const Vector2d& xiEnd) const {
  const double T = params_.stepDuration;
  const Vector2d lead = (z.p1 - z.p0) / (T * omega_);
  return z.p0 + lead + (xiEnd - z.p1 - lead) * std::exp(-omega_ * T);
}

Vector2d Walk::dcmAtEnd(const StepZmp& z, const Vector2d& xi, double t) const {
  const double T = params_.stepDuration;
  const Vector2d lead = (z.p1 - z.p0) / (T * omega_);
  return z.p1 + lead + (xi - zmpAt(z, t) - lead) * std::exp(omega_ * std::max(0.0, T - t));
}

// The DCM's offset from the landing step's first ZMP at touch-down in the gait that continues
// with the current speed: the backward recursion xi_start(k) = f(xi_end(k)) over the next
// footsteps (its end condition fades with e^(-omega T N)).
Vector2d Walk::periodicOffset(const Pose2& support, bool supportLeft, const Pose2& target) const {
  std::array<Pose2, kPreviewSteps + 2> feet;
  feet[0] = support;
  feet[1] = target;
  bool left = !supportLeft;  // the side of feet[1]
  for (int k = 2; k < kPreviewSteps + 2; ++k) {
    left = !left;
    feet[k] = nominalTarget(feet[k - 1], left, speed_);
  }
  // feet[k] (k >= 1) supports step k; its side alternates starting with !supportLeft.
  std::array<StepZmp, kPreviewSteps + 1> zmp;
  for (int k = 1; k <= kPreviewSteps; ++k) {
    const bool sideLeft = (k % 2 == 1) ? !supportLeft : supportLeft;
    zmp[k] = stepZmp(feet[k], sideLeft, feet[k - 1], feet[k + 1]);
  }
  Vector2d xi = zmp[kPreviewSteps].p1;
  for (int k = kPreviewSteps; k >= 1; --k) xi = dcmAtStart(zmp[k], xi);
  return xi - zmp[1].p0;
}

void Walk::updateSpeed(const Pose2& request) {
  const Pose2 goal = stopRequested_ ? Pose2() : clipSpeed(request);
  const double T = params_.stepDuration;
  speed_.x = towards(speed_.x, goal.x, params_.accelForward * T);
  speed_.y = towards(speed_.y, goal.y, params_.accelSide * T);
  speed_.theta = towards(speed_.theta, goal.theta, params_.accelTurn * T);
}

void Walk::startStep(double) {
  t_ = 0;
  stepDuration_ = params_.stepDuration;
  support_ = supportLeft_ ? left_ : right_;
  swingStart_ = supportLeft_ ? right_ : left_;
  headingCorrection_ = std::clamp(-params_.headingGain * yawError_, -params_.maxHeadingCorrection, params_.maxHeadingCorrection);
  swingTarget_ = nominalTarget(support_, !supportLeft_, speed_);
  swingTarget_.theta = Pose2::wrap(swingTarget_.theta + headingCorrection_);
  ++steps_;
}

bool Walk::closedFeet() const {
  const Pose2 rel = right_.inverse() * left_;
  return std::abs(rel.x) < 0.004 && std::abs(rel.y - params_.footSpacing) < 0.004 && std::abs(rel.theta) < 0.03;
}

void Walk::integrateModel(const Vector2d& zmp, double dt) {
  // Exact LIPM over dt with the ZMP held.
  const double ch = std::cosh(omega_ * dt), sh = std::sinh(omega_ * dt);
  const Vector2d c = zmp + (c_ - zmp) * ch + cd_ / omega_ * sh;
  const Vector2d cd = (c_ - zmp) * omega_ * sh + cd_ * ch;
  c_ = c;
  cd_ = cd;
  zmp_ = zmp;
}

JointArray Walk::solve(const Foot3& left, const Foot3& right, double torsoYaw, const Eigen::Matrix3d& leftCorrection,
                       const Eigen::Matrix3d& rightCorrection, int swingSide) {
  JointArray joints = arms_;
  for (int iter = 0; iter < 3; ++iter) {
    Isometry3d torso = Isometry3d::Identity();
    torso.translation() = Vector3d(torsoXY_.x(), torsoXY_.y(), params_.torsoHeight);
    torso.linear() = rotZ(torsoYaw) * rotY(params_.torsoPitch);
    const Isometry3d inv = torso.inverse();
    Isometry3d l = inv * footIsometry(left.pose, left.z), r = inv * footIsometry(right.pose, right.z);
    // Corrections (torso frame): a swing foot turns about the support sole, a support foot about itself.
    if (swingSide == 1) l.translation() = r.translation() + leftCorrection * (l.translation() - r.translation());
    if (swingSide == -1) r.translation() = l.translation() + rightCorrection * (r.translation() - l.translation());
    l.linear() = leftCorrection * l.linear();
    r.linear() = rightCorrection * r.linear();
    if (params_.levelSoles) {
      // The sole seen level by the (offset) joint angles stands tilted by -level in truth.
      l.linear() = l.linear() * rotX(level_[0].x()) * rotY(level_[0].y());
      r.linear() = r.linear() * rotX(level_[1].x()) * rotY(level_[1].y());
    }
    legsIK(l, r, joints);
    torso_ = torso;
    if (iter == 2) break;
    const Vector3d com = torso * centerOfMass(joints);
    torsoXY_ += c_ - com.head<2>();
  }
  return joints;
}

JointRequest Walk::update(const SensorFrame& frame, const Pose2& request, bool stop) {
  const double dt = lastTime_ < 0 ? kNominalCycle : std::clamp(frame.time - lastTime_, 0.0, 0.05);
  lastTime_ = frame.time;
  const bool wantMove = !stop && (std::abs(request.x) > 1e-4 || std::abs(request.y) > 1e-4 || std::abs(request.theta) > 1e-4);
  stopRequested_ = stop;
  gyroFiltered_ = 0.7 * gyroFiltered_ + 0.3 * frame.inertial.gyroscope.head<2>();
  // Heading: how much more the robot turned than the applied speed asked (feet slipping about
  // the vertical), from the gyro; the next steps turn it back.
  if (phase_ == Phase::Walking || phase_ == Phase::Starting) {
    const double yawRate = yawRateOf(frame);
    yawError_ += (yawRate - speed_.theta) * dt;
  } else {
    yawError_ = 0;
  }

  Foot3 left{left_, 0}, right{right_, 0};
  double torsoYaw = meanAngle(left_.theta, right_.theta);

  switch (phase_) {
    case Phase::Standing: {
      if (wantMove) {
        phase_ = Phase::Starting;
        t_ = 0;
        updateSpeed(request);
        // The first swing foot: towards the side the robot goes (left when none).
        const Pose2 s = clipSpeed(request);
        supportLeft_ = s.y < -1e-4 || (std::abs(s.y) <= 1e-4 && s.theta < -1e-4);
      }
      const Vector2d mid = (left_.translation() + right_.translation()) / 2;
      integrateModel(mid + (c_ + cd_ / omega_ - mid) * 2.0, dt);  // ZMP control: the DCM settles at mid
      break;
    }
    case Phase::Starting: {
      // Double support: a ZMP that brings the DCM to where the first step needs it at its start.
      const Pose2 support = supportLeft_ ? left_ : right_;
      const Pose2 swing = supportLeft_ ? right_ : left_;
      const Pose2 target = nominalTarget(support, !supportLeft_, speed_);
      const StepZmp first = stepZmp(support, supportLeft_, swing, target);
      const Vector2d xiEnd = stepZmp(target, !supportLeft_, support, nominalTarget(target, supportLeft_, speed_)).p0 +
                             periodicOffset(support, supportLeft_, target);
      const Vector2d xiStart = dcmAtStart(first, xiEnd);
      const double remaining = std::max(params_.startDuration - t_, dt);
      const double e = std::exp(omega_ * remaining);
      const Vector2d xi = c_ + cd_ / omega_;
      Vector2d zmp = (xiStart - xi * e) / (1 - e);
      // Keep it between the feet.
      const Vector2d a = zmpOf(left_, true), b = zmpOf(right_, false);
      const Vector2d ab = b - a;
      const double u = std::clamp((zmp - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      zmp = a + u * ab + (zmp - a - u * ab).cwiseMax(-0.03).cwiseMin(0.03);
      integrateModel(zmp, dt);
      t_ += dt;
      if (t_ >= params_.startDuration - 1e-9) {
        phase_ = Phase::Walking;
        startStep(frame.time);
      }
      break;
    }
    case Phase::Walking: {
      t_ += dt;
      // Touch-down on time. (Ending a step early when the swing foot's FSRs already carry
      // weight was tried and measured worse: the model's step timing then differs from the
      // plan's, and on a randomised robot the next steps' adjustment ran into the reach limits.)
      if (t_ >= stepDuration_ - 1e-9) {
        (supportLeft_ ? right_ : left_) = swingTarget_;
        landedLeft_ = !supportLeft_;
        landCorrection_ = swingCorrection_;
        landTime_ = frame.time;
        supportLeft_ = !supportLeft_;
        updateSpeed(request);
        if (stopRequested_ && std::abs(speed_.x) < 1e-3 && std::abs(speed_.y) < 1e-3 && std::abs(speed_.theta) < 1e-3 &&
            closedFeet()) {
          phase_ = Phase::Stopping;
          t_ = 0;
          left = {left_, 0};
          right = {right_, 0};
          torsoYaw = meanAngle(left_.theta, right_.theta);
          integrateModel(c_ + cd_ / omega_, dt);
          break;
        }
        startStep(frame.time);
      }
      measureState(frame, dt);
      Pose2 nominal = nominalTarget(support_, !supportLeft_, speed_);
      nominal.theta = Pose2::wrap(nominal.theta + headingCorrection_);
      const StepZmp zmp = stepZmp(support_, supportLeft_, swingStart_, nominal);
      // Step adjustment: send the swing foot where the DCM predicts it must land.
      if (t_ < params_.adjustUntilPhase * stepDuration_) {
        const Vector2d b = periodicOffset(support_, supportLeft_, nominal);
        const Vector2d xiEnd = dcmAtEnd(zmp, c_ + cd_ / omega_, t_);
        const Vector2d landZmp = stepZmp(nominal, !supportLeft_, support_, nominalTarget(nominal, supportLeft_, speed_)).p0;
        const Vector2d shift = xiEnd - b - landZmp;
        Pose2 target = nominal;
        target.x += shift.x();
        target.y += shift.y();
        swingTarget_ = clipTarget(support_, !supportLeft_, target);
        if (debug_->on(kWalkTrace) && std::abs(t_ - 0.5 * stepDuration_) < dt / 2) {
          const Pose2 n = support_.inverse() * nominal, a = support_.inverse() * target, c = support_.inverse() * swingTarget_;
          debug_->write(kWalkTrace, {{"support", supportLeft_ ? "left" : "right"},
                                     {"nominal", {n.x, n.y, n.theta * 180 / M_PI}},
                                     {"adjusted", {a.x, a.y}},
                                     {"clipped", {c.x, c.y}},
                                     {"speed", {speed_.x, speed_.y, speed_.theta * 180 / M_PI}}});
        }
      }
      integrateModel(zmpAt(zmp, t_ + dt / 2), dt);
      const double s = std::clamp(t_ / stepDuration_, 0.0, 1.0);
      const double h = smooth5(s);
      Foot3 swing;
      swing.pose = {swingStart_.x + h * (swingTarget_.x - swingStart_.x), swingStart_.y + h * (swingTarget_.y - swingStart_.y),
                    Pose2::wrap(swingStart_.theta + h * Pose2::wrap(swingTarget_.theta - swingStart_.theta))};
      swing.z = params_.stepHeight * (1 - std::cos(2 * M_PI * s)) / 2;
      const Foot3 support{support_, 0};
      left = supportLeft_ ? support : swing;
      right = supportLeft_ ? swing : support;
      torsoYaw = meanAngle(support_.theta, swing.pose.theta);
      break;
    }
    case Phase::Stopping: {
      // Double support: the DCM is led to the feet's midpoint, the COM follows.
      const Vector2d mid = (left_.translation() + right_.translation()) / 2;
      const Vector2d xi = c_ + cd_ / omega_;
      integrateModel(xi + (xi - mid) * 1.5, dt);
      t_ += dt;
      if ((c_ - mid).norm() < 0.002 && cd_.norm() < 0.01) phase_ = Phase::Standing;
      if (wantMove) {
        phase_ = Phase::Starting;
        t_ = 0;
        updateSpeed(request);
      }
      break;
    }
  }

  if (phase_ != Phase::Walking) measureState(frame, dt);  // no single support: no comparison
  if (phase_ == Phase::Standing) estimateLevel(frame, dt);

  // Tilt corrections. The swing sole is kept parallel to the ground (and its position relative
  // to the support sole right in the world) by undoing the torso's measured tilt beyond the
  // planned one: d_torso = R_measured^T R_planned d_planned. It fades in while the foot lifts;
  // after touch-down the landed foot keeps it and lets it decay, so nothing jumps.
  const Eigen::Matrix3d tiltError = torsoTilt(frame.inertial.angle.x(), frame.inertial.angle.y()).transpose() *
                                    rotY(params_.torsoPitch);
  const Eigen::AngleAxisd tiltErrorAA(tiltError);
  Eigen::Matrix3d corrL = Eigen::Matrix3d::Identity(), corrR = Eigen::Matrix3d::Identity();
  int swingSide = 0;
  const double decay = std::exp(-(frame.time - landTime_) / params_.landingCorrectionDecay);
  const Eigen::Matrix3d landed = rotationOf(decay * landCorrection_);
  (landedLeft_ ? corrL : corrR) = landed;
  if (phase_ == Phase::Walking) {
    const double s = std::clamp(t_ / stepDuration_, 0.0, 1.0);
    const double w = params_.swingTiltCompensation * smooth5(s / 0.3);
    const Eigen::Matrix3d swingCorr = Eigen::AngleAxisd(w * tiltErrorAA.angle(), tiltErrorAA.axis()).toRotationMatrix();
    swingSide = supportLeft_ ? -1 : 1;
    (supportLeft_ ? corrR : corrL) = swingCorr;
    swingCorrection_ = w * tiltErrorAA.angle() * tiltErrorAA.axis();
  }
  JointRequest out;
  out.position = solve(left, right, torsoYaw, corrL, corrR, swingSide);
  // Velocity lead: the servos' damping acts on the joint speed, so a moving joint trails its
  // target by about (kd / kp) q'; aiming leadTime ahead along the trajectory cancels that.
  {
    const JointArray ik = out.position;
    if (havePreviousIK_ && dt > 1e-6)
      for (BodySide side : {BodySide::Left, BodySide::Right}) {
        const bool swing = phase_ == Phase::Walking && (side == BodySide::Left) != supportLeft_;
        const double lead = swing ? params_.leadTime : params_.supportLeadTime;
        for (Joint j : legJointIds(side)) {
          if (j == LHipYawPitch) continue;
          out.position[j] += lead * (ik[j] - previousIK_[j]) / dt;
        }
      }
    previousIK_ = ik;
    havePreviousIK_ = true;
  }
  // The legs' share of the weight from the FSRs (what they actually carry), smoothed.
  const double fsrL = frame.fsr.total(true), fsrR = frame.fsr.total(false);
  if (fsrL + fsrR > 0.5) leftShare_ = 0.6 * leftShare_ + 0.4 * fsrL / (fsrL + fsrR);
  compensateSag(out.position, left, right, leftShare_);
  // Gyro damping on the support ankle(s).
  const bool single = phase_ == Phase::Walking;
  for (bool isLeft : {true, false}) {
    if (single && isLeft != supportLeft_) continue;
    out.position[isLeft ? LAnklePitch : RAnklePitch] += params_.gyroPitchGain * gyroFiltered_.y();
    out.position[isLeft ? LAnkleRoll : RAnkleRoll] += params_.gyroRollGain * gyroFiltered_.x();
  }
  out.stiffness.fill(1.0);
  lastCommand_ = out.position;
  return out;
}

// The COM as the sensors see it: from the support sole through the measured joint angles, the
// body tilted as the IMU says; in the plan frame, the support sole where the plan put it.
// Its difference to the model's COM (and that difference's rate) is what the model does not
// know: the body tipping about a sole edge, joints lagging, a foot landing elsewhere.
void Walk::measureState(const SensorFrame& frame, double dt) {
  if (phase_ != Phase::Walking) {
    haveMeasurement_ = false;
    comError_.setZero();
    comErrorRate_.setZero();
    return;
  }
  const bool left = supportLeft_;
  const Eigen::Matrix3d tilt = torsoTilt(frame.inertial.angle.x(), frame.inertial.angle.y());
  const Isometry3d sole = torsoToSole(frame.joints.position, left ? BodySide::Left : BodySide::Right);
  const Vector3d d = tilt * (centerOfMass(frame.joints.position) - sole.translation());
  const Vector3d soleX = tilt * sole.linear().col(0);
  const double yaw = std::atan2(soleX.y(), soleX.x());
  const Vector2d local = rotZ(-yaw).topLeftCorner<2, 2>() * d.head<2>();
  const Vector2d error = (left ? left_ : right_) * local - c_;
  if (haveMeasurement_ && measuredLeft_ == left && dt > 1e-6)
    comErrorRate_ += 0.3 * ((error - comError_) / dt - comErrorRate_);
  comError_ = error;
  measuredLeft_ = left;
  haveMeasurement_ = true;
}

// Standing quietly on both feet the floor holds the soles flat; the measured joint angles and
// the IMU's tilt then put each sole at the roll and pitch that the leg's joint offsets (hip,
// knee, ankle) add up to, negated. Averaged, that is what the IK targets turn back, so the
// swing foot lands flat and the support foot is not loaded on an edge: a sole pitched by 1 deg
// made the robot crab sideways by 25 cm over 2.7 m (the feet slipping), beyond the odometry.
void Walk::estimateLevel(const SensorFrame& frame, double dt) {
  if (!params_.levelSoles || dt <= 0) return;
  const double fl = frame.fsr.total(true), fr = frame.fsr.total(false);
  if (fl + fr < 0.5 || std::min(fl, fr) < 0.25 * (fl + fr)) return;  // not on both feet
  if (frame.inertial.gyroscope.norm() > 0.15) return;                 // not quiet
  const Eigen::Matrix3d tilt = torsoTilt(frame.inertial.angle.x(), frame.inertial.angle.y());
  // Averaging (1 / n) at first, then a moving average with the time constant.
  levelWeight_ = std::min(levelWeight_ + dt, params_.levelTime);
  const double a = dt / levelWeight_;
  for (int side = 0; side < 2; ++side) {
    const Eigen::Matrix3d w = tilt * torsoToSole(frame.joints.position, side == 0 ? BodySide::Left : BodySide::Right).linear();
    const Vector2d rp(std::atan2(w(2, 1), w(2, 2)), std::atan2(-w(2, 0), std::hypot(w(2, 1), w(2, 2))));
    const Vector2d goal = rp.cwiseMax(-params_.maxLevelCorrection).cwiseMin(params_.maxLevelCorrection);
    // Slew-limited: the first estimate is a full step (a = 1), and a sudden 4 deg change of every
    // IK target would jerk the robot (LoLA peer test: targets move <= 0.05 rad per cycle).
    const Vector2d change = a * (goal - level_[side]);
    level_[side] += change.cwiseMax(-params_.maxLevelRate * dt).cwiseMin(params_.maxLevelRate * dt);
  }
}

void Walk::compensateSag(JointArray& joints, const Foot3& left, const Foot3& right, double leftShare) const {
  if (params_.sagCompensation <= 0) return;
  // The ground's force on the robot: gravity and the LIPM's horizontal push, in the torso frame.
  const Vector2d horizontal = omega_ * omega_ * (c_ - zmp_);
  const Vector3d force = torso_.linear().transpose() * (totalMass() * Vector3d(horizontal.x(), horizontal.y(), kGravity));
  const Isometry3d inv = torso_.inverse();
  double hyp = 0;
  for (bool isLeft : {true, false}) {
    const double share = isLeft ? leftShare : 1 - leftShare;
    if (share <= 0) continue;
    const Foot3& foot = isLeft ? left : right;
    const Vector2d p = zmpOf(foot.pose, isLeft);
    const Vector3d point = inv * Vector3d(p.x(), p.y(), foot.z);
    const auto tau = legJointTorques(joints, isLeft ? BodySide::Left : BodySide::Right, point, share * force);
    const auto ids = legJointIds(isLeft ? BodySide::Left : BodySide::Right);
    hyp += tau[0];
    for (int i = 1; i < 6; ++i) joints[ids[i]] += params_.sagCompensation * tau[i] / params_.servoGain;
  }
  joints[LHipYawPitch] += params_.sagCompensation * hyp / params_.servoGain;
}

void Walk::updateOdometry(const SensorFrame& frame, bool rotationOnly) {
  const double dt = odometryTime_ < 0 ? 0.0 : std::clamp(frame.time - odometryTime_, 0.0, 0.05);
  odometryTime_ = frame.time;
  // Each sole in the torso's yaw-free frame (the leg's joint angles turned by the IMU's tilt).
  const Eigen::Matrix3d tilt = torsoTilt(frame.inertial.angle.x(), frame.inertial.angle.y());
  std::array<Isometry3d, 2> soles;  // [left, right]
  for (int side = 0; side < 2; ++side)
    soles[side] = Isometry3d(tilt) * torsoToSole(frame.joints.position, side == 0 ? BodySide::Left : BodySide::Right);
  // The turn: the torso's attitude carried on by the gyro (the cycle's mean rate, torso frame)
  // from last cycle's measured tilt, its change of heading. Integrating the Euler yaw rate
  // instead (the rate turned by this cycle's roll and pitch) misses the coupling of the
  // stride's roll and yaw wobble: measured turning in place, it overstated every turn by
  // 0.12 % (1.4 deg in 1100 deg; this way 0.01 deg): after turning to a target behind it, a
  // 3 m walk-to ended 1 cm off across its path.
  const Eigen::Matrix3d carried = lastTilt_ * rotationOf(dt * frame.inertial.gyroscope);
  const double turn = std::atan2(carried(1, 0), carried(0, 0));
  lastTilt_ = tilt;
  // The motion since the last cycle relative to the feet on the ground (a loaded foot does not
  // move), each foot weighted by the weight it carried: while the weight passes from one foot
  // to the other both slip a little, the lightly loaded one more. The heading from the gyro.
  // The point of a sole that stays put is where it touches the ground: a foot landing on its
  // heel or rolling onto its toes turns about that edge, and the point below the ankle moves by
  // millimetres while it does. So each foot's motion is taken at its ground contact (from its
  // FSRs, this cycle), the same sole point in both cycles.
  const Vector2d imuDelta =
      imuVelocity_.update(tilt, frame.inertial.accelerometer, frame.inertial.gyroscope, turn, dt, Vector3d(dims::kImuX, dims::kImuY, dims::kImuZ));
  // The inertial check only with an accelerometer that reads +g upwards on average (about 1 s):
  // a sign convention other than the simulator's, or a broken sensor, leaves the kinematics alone.
  const double up = (tilt * frame.inertial.accelerometer).z();
  if (std::isfinite(up)) gravityReading_ += 0.02 * (up - gravityReading_);
  const bool imuPlausible = std::abs(gravityReading_ - kGravity) < 2.0;
  if (haveRelative_ && !rotationOnly) {
    const bool inertial = params_.inertialOdometry && imuPlausible && dt > 1e-6;
    std::array<Pose2, 2> d;
    for (int side = 0; side < 2; ++side) {
      const Vector3d contact = groundContact(frame, side == 0);
      const Pose2 before = robotInSole(lastSoles_[side], contact), after = robotInSole(soles[side], contact);
      // A loaded sole that twists (the gyro turned more than the leg did) turns about its
      // contact, carrying the robot frame along an arc: with the robot frame 5-10 cm from the
      // contact, a 1 deg twist moves it 1-2 mm sideways, which turning the robot frame about
      // its own origin misses (the largest part of a randomised walk-to's error across its path).
      // Only with the inertial check: a foot in the air "twists" too, and without the check
      // that wrong arc was followed (a 9 cm walk-to trial).
      const double twist =
          params_.twistAboutContact && inertial ? Pose2::wrap(turn - Pose2::wrap(after.theta - before.theta)) : 0.0;
      d[side] = before.inverse() * Pose2(0, 0, twist) * after;
    }
    double w = std::pow(odometryLeftShare_, params_.odometryLoadExponent);
    double wr = std::pow(1 - odometryLeftShare_, params_.odometryLoadExponent);
    // A foot the walk has begun to lift is no reference even while its FSRs still read weight:
    // it is being dragged off the ground (measured: up to 8 mm a cycle the wrong way when the
    // other foot had landed late and was still bouncing on its heel).
    if (phase_ == Phase::Walking && t_ > params_.odometrySwingAfter) (supportLeft_ ? wr : w) = 0;
    const double k = inertial ? params_.odometryScale : params_.kinematicOdometryScale;
    Pose2 delta;
    if (!imuPlausible) inertial_.reset();
    if (inertial) {
      // The feet's velocities checked against the IMU's prediction (InertialOdometry.h).
      const Vector2d v = inertial_.update(dt, lastTurn_, imuDelta, Vector2d(d[0].x, d[0].y) / dt, w, Vector2d(d[1].x, d[1].y) / dt, wr);
      delta = Pose2(k * v.x() * dt, k * v.y() * dt, 0);
    } else {
      const double a = w + wr > 1e-9 ? w / (w + wr) : (supportLeft_ ? 1.0 : 0.0);
      delta = Pose2(k * (a * d[0].x + (1 - a) * d[1].x), k * (a * d[0].y + (1 - a) * d[1].y), a * d[0].theta + (1 - a) * d[1].theta);
    }
    if (params_.gyroOdometry || params_.inertialOdometry) delta.theta = turn;
    odometry_ = odometry_ * delta;
  } else {
    odometry_.theta = Pose2::wrap(odometry_.theta + turn);
    inertial_.reset();
  }
  lastTurn_ = turn;
  lastSoles_ = soles;
  // The feet's centre in the robot frame (each sole's pose is the inverse of the robot's in it).
  const Pose2 l = robotInSole(soles[0], Vector3d::Zero()).inverse(), r = robotInSole(soles[1], Vector3d::Zero()).inverse();
  const Pose2 centre((l.x + r.x) / 2, (l.y + r.y) / 2, meanAngle(l.theta, r.theta));
  standPoseEstimate_ = odometry_ * centre * standOffset_;
  // Stopping now, the swing foot lands where the plan sends it and the other foot closes beside it.
  Pose2 stopCentre = centre;
  if (phase_ == Phase::Walking) {
    const Pose2 supportInRobot = robotInSole(soles[supportLeft_ ? 0 : 1], Vector3d::Zero()).inverse();
    const Pose2 landing = supportInRobot * (support_.inverse() * swingTarget_);
    stopCentre = landing * Pose2(0, (supportLeft_ ? 1.0 : -1.0) * params_.footSpacing / 2, 0);
  }
  stopPoseEstimate_ = odometry_ * stopCentre * standOffset_;
  haveRelative_ = !rotationOnly;
  const double fl = frame.fsr.total(true), fr = frame.fsr.total(false);
  if (fl + fr > 0.5) odometryLeftShare_ = fl / (fl + fr);
}

}  // namespace nao
