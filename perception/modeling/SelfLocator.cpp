#include "perception/modeling/SelfLocator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "perception/Geometry.h"
#include "perception/modeling/ViewRegion.h"

namespace nao {
namespace modeling_detail {

using Vec2 = Eigen::Vector2d;

// One usable percept element of an image, robot frame.
struct Element {
  enum class Kind { Line, Intersection, Circle, PenaltyMark } kind = Kind::Line;
  FieldIntersection::Type type = FieldIntersection::Type::L;
  Vec2 p = Vec2::Zero();   // point, or the line's centre
  Vec2 u = Vec2::UnitX();  // line direction (unit)
  double length = 0;       // line length (its ends: p -+ u length / 2)
  double sigmaP = 0.05;    // m
  double sigmaA = 0.05;    // rad (lines)
  int lineIndex = -1;      // index into LinesPercept::lines (lines)
};

}  // namespace modeling_detail

namespace {

constexpr double kPi = std::numbers::pi;
using modeling_detail::Element;
using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;

bool finite2(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

FieldIntersection::Type toFieldType(LinesPercept::Intersection::Type t) {
  switch (t) {
    case LinesPercept::Intersection::Type::L: return FieldIntersection::Type::L;
    case LinesPercept::Intersection::Type::T: return FieldIntersection::Type::T;
    case LinesPercept::Intersection::Type::X: return FieldIntersection::Type::X;
  }
  return FieldIntersection::Type::X;
}

std::vector<Element> elementsOf(const FieldPercepts& in, const SelfLocator::Params& prm, int& skipped) {
  std::vector<Element> out;
  const PerceptUncertainty& un = in.uncertainty;
  auto sigmaAt = [&](const Vec2& p) { return std::max(1e-3, un.sigmaBase + un.sigmaPerMetre * p.norm()); };
  auto usable = [&](const Vec2& p) { return finite2(p) && p.norm() <= prm.maxPerceptDistance; };
  for (std::size_t i = 0; i < in.lines.lines.size(); ++i) {
    const auto& l = in.lines.lines[i];
    if (!usable(l.from) || !usable(l.to)) {
      ++skipped;
      continue;
    }
    const Vec2 d = l.to - l.from;
    const double len = d.norm();
    if (!(len >= prm.minLineLength)) continue;
    Element e;
    e.kind = Element::Kind::Line;
    e.p = 0.5 * (l.from + l.to);
    e.u = d / len;
    e.length = len;
    e.sigmaP = sigmaAt(e.p);
    // The angle of a segment fitted through two noisy ends is no better than this.
    e.sigmaA = std::max(un.sigmaAngle + un.sigmaAnglePerMetre * e.p.norm(),
                        std::sqrt(2.0) * sigmaAt(e.p) / len);
    e.lineIndex = static_cast<int>(i);
    out.push_back(e);
  }
  for (const auto& x : in.lines.intersections) {
    if (!usable(x.position)) {
      ++skipped;
      continue;
    }
    Element e;
    e.kind = Element::Kind::Intersection;
    e.type = toFieldType(x.type);
    e.p = x.position;
    e.sigmaP = sigmaAt(e.p);
    out.push_back(e);
  }
  if (in.lines.circle.found) {
    if (usable(in.lines.circle.centre)) {
      Element e;
      e.kind = Element::Kind::Circle;
      e.p = in.lines.circle.centre;
      e.sigmaP = sigmaAt(e.p);
      out.push_back(e);
    } else {
      ++skipped;
    }
  }
  if (in.lines.penaltyMark) {
    if (usable(*in.lines.penaltyMark)) {
      Element e;
      e.kind = Element::Kind::PenaltyMark;
      e.p = *in.lines.penaltyMark;
      e.sigmaP = sigmaAt(e.p);
      out.push_back(e);
    } else {
      ++skipped;
    }
  }
  return out;
}

// A pose with its sine and cosine, to move many field points into its robot frame.
struct PoseFrame {
  Vec3 x;
  double c, s;
  explicit PoseFrame(const Vec3& pose) : x(pose), c(std::cos(pose.z())), s(std::sin(pose.z())) {}
  Vec2 toRobot(const Vec2& p) const {
    const double dx = p.x() - x.x(), dy = p.y() - x.y();
    return {c * dx + s * dy, -s * dx + c * dy};
  }
};

// How many field elements an element can be associated with, and the residual
// (measurement minus prediction, 0 when it fits) for one of them at pose x.
class Associator {
 public:
  Associator(const FieldModel& f, const SelfLocator::Params& p) : f_(f), p_(p) {}

  int count(const Element& e) const {
    switch (e.kind) {
      case Element::Kind::Line: return static_cast<int>(f_.lines.size());
      case Element::Kind::Intersection: return static_cast<int>(f_.intersections.size());
      case Element::Kind::Circle: return 1;
      case Element::Kind::PenaltyMark: return static_cast<int>(f_.penaltyCrosses.size());
    }
    return 0;
  }

  // False when the pair cannot fit at all (wrong type, no overlap).
  bool residual(const Element& e, int j, const PoseFrame& x, Vec2& r) const {
    switch (e.kind) {
      case Element::Kind::Line: {
        const Vec2 a = x.toRobot(f_.lines[j].from), b = x.toRobot(f_.lines[j].to);
        const double len = (b - a).norm();
        if (len < 1e-9) return false;
        Vec2 v = (b - a) / len;
        Vec2 a0 = a;
        if (v.dot(e.u) < 0) {
          v = -v;
          a0 = b;
        }
        const Vec2 n(-v.y(), v.x());
        // Both ends of the measured segment lie along the model line (with the margin).
        const double s = v.dot(e.p - a0), half = 0.5 * e.length * std::abs(v.dot(e.u));
        if (s - half < -p_.lineEndMargin || s + half > len + p_.lineEndMargin) return false;
        r = Vec2(n.dot(e.p - a0), normalizeAngle(std::atan2(e.u.y(), e.u.x()) - std::atan2(v.y(), v.x())));
        return true;
      }
      case Element::Kind::Intersection:
        if (f_.intersections[j].type != e.type) return false;
        r = e.p - x.toRobot(f_.intersections[j].position);
        return true;
      case Element::Kind::Circle:
        r = e.p - x.toRobot(f_.centerCircleCenter);
        return true;
      case Element::Kind::PenaltyMark:
        r = e.p - x.toRobot(f_.penaltyCrosses[j]);
        return true;
    }
    return false;
  }

  // H = d(prediction)/dx = -d(residual)/dx, numerically.
  Eigen::Matrix<double, 2, 3> jacobian(const Element& e, int j, const Vec3& x, const Vec2& r0) const {
    Eigen::Matrix<double, 2, 3> h;
    for (int k = 0; k < 3; ++k) {
      Vec3 xk = x;
      const double eps = 1e-6;
      xk[k] += eps;
      Vec2 rk;
      if (!residual(e, j, PoseFrame(xk), rk)) rk = r0;
      Vec2 d = rk - r0;
      if (e.kind == Element::Kind::Line) d.y() = normalizeAngle(d.y());
      h.col(k) = -d / eps;
    }
    return h;
  }

  Mat2 noise(const Element& e) const {
    Mat2 r = Mat2::Zero();
    r(0, 0) = e.sigmaP * e.sigmaP;
    r(1, 1) = e.kind == Element::Kind::Line ? e.sigmaA * e.sigmaA : e.sigmaP * e.sigmaP;
    return r;
  }

  // The metric gate: a corridor for lines (distance, angle), a radius for points.
  bool inMetricGate(const Element& e, const Vec2& r, const Mat2& hph) const {
    // Widened by the hypothesis' own uncertainty; a line's angle by at most maxAngleWidening (all
    // field lines are parallel or square to each other: a wide gate would take a square one).
    const double w0 = 2 * std::sqrt(std::max(0.0, hph(0, 0)));
    const double w1raw = 2 * std::sqrt(std::max(0.0, hph(1, 1)));
    const double w1 = e.kind == Element::Kind::Line ? std::min(w1raw, p_.maxAngleWidening) : w1raw;
    switch (e.kind) {
      case Element::Kind::Line: return std::abs(r.x()) <= p_.lineGate + w0 && std::abs(r.y()) <= p_.lineAngleGate + w1;
      case Element::Kind::Intersection: return r.norm() <= p_.intersectionGate + std::max(w0, w1);
      case Element::Kind::Circle: return r.norm() <= p_.circleGate + std::max(w0, w1);
      case Element::Kind::PenaltyMark: return r.norm() <= p_.penaltyMarkGate + std::max(w0, w1);
    }
    return false;
  }

  struct Match {
    int j = -1;
    Vec2 r = Vec2::Zero();
    Eigen::Matrix<double, 2, 3> h = Eigen::Matrix<double, 2, 3>::Zero();
    Mat2 s = Mat2::Identity();
    double d2 = 0;
  };

  // The best-fitting field element for e at mean x with covariance P (P may be zero).
  bool associate(const Element& e, const Vec3& x, const Mat3& P, Match& best) const {
    bool found = false;
    const Mat2 R = noise(e);
    // Bounds of H P H' from P alone (position, heading times the percept's distance).
    const double sp = std::sqrt(std::max(P(0, 0), P(1, 1))), sa = std::sqrt(std::max(0.0, P(2, 2)));
    const double wp = sp + sa * e.p.norm();
    Mat2 pregate = Mat2::Zero();
    pregate(0, 0) = wp * wp;
    pregate(1, 1) = e.kind == Element::Kind::Line ? sa * sa : wp * wp;
    const PoseFrame frame(x);
    for (int j = 0; j < count(e); ++j) {
      Vec2 r;
      if (!residual(e, j, frame, r)) continue;
      // Cheap pre-gate before the Jacobian: the widest the metric gate can be at this P.
      if (!inMetricGate(e, r, pregate)) continue;
      const Eigen::Matrix<double, 2, 3> h = jacobian(e, j, x, r);
      const Mat2 hph = h * P * h.transpose();
      if (!inMetricGate(e, r, hph)) continue;
      const Mat2 s = hph + R;
      const double d2 = r.dot(s.ldlt().solve(r));
      if (!std::isfinite(d2) || d2 > p_.chi2Gate) continue;
      if (!found || d2 < best.d2) {
        best = {j, r, h, s, d2};
        found = true;
      }
    }
    return found;
  }

 private:
  const FieldModel& f_;
  const SelfLocator::Params& p_;
};

Mat3 sanitised(const Mat3& c, double maxVar) {
  Mat3 s = 0.5 * (c + c.transpose());
  for (int i = 0; i < 3; ++i) s(i, i) = std::clamp(s(i, i), 1e-10, maxVar);
  return s;
}

bool finite(const SelfLocator::Hypothesis& h) { return h.mean.allFinite() && h.cov.allFinite(); }

Vec3 toVec(const Pose2& p) { return {p.x, p.y, p.theta}; }
Pose2 toPose(const Vec3& v) { return {v.x(), v.y(), normalizeAngle(v.z())}; }

// Rotation by theta applied to v.
Vec2 rot(double theta, const Vec2& v) {
  const double c = std::cos(theta), s = std::sin(theta);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

// The pose that maps the robot-frame point pr to the field point pf with heading theta.
Pose2 poseFrom(double theta, const Vec2& pf, const Vec2& pr) {
  const Vec2 t = pf - rot(theta, pr);
  return {t.x(), t.y(), normalizeAngle(theta)};
}

double angleOf(const Vec2& v) { return std::atan2(v.y(), v.x()); }

}  // namespace

Pose2 SelfLocator::mirror(const Pose2& p) { return {-p.x, -p.y, normalizeAngle(p.theta + kPi)}; }

SelfLocator::SelfLocator(const FieldModel& field, const Params& params) : field_(field), params_(params) {
  // Each L and T with the unit directions of the lines that leave it.
  for (const auto& x : field_.intersections) {
    if (x.type == FieldIntersection::Type::X) continue;
    ModelCorner c{x.type, x.position, {}};
    for (const auto& l : field_.lines) {
      const Vec2 d = l.to - l.from;
      const double len = d.norm();
      const Vec2 u = d / len;
      const double s = u.dot(x.position - l.from);
      const double off = std::abs(Vec2(-u.y(), u.x()).dot(x.position - l.from));
      if (off > 1e-6 || s < -1e-6 || s > len + 1e-6) continue;
      if (s > 1e-6) c.arms.push_back(-u);
      if (s < len - 1e-6) c.arms.push_back(u);
    }
    corners_.push_back(c);
  }
  constexpr int kChords = 32;
  for (int i = 0; i < kChords; ++i) {
    auto at = [&](int k) {
      const double a = 2 * kPi * k / kChords;
      return Vec2(field_.centerCircleCenter + field_.centerCircleRadius * Vec2(std::cos(a), std::sin(a)));
    };
    circleChords_.emplace_back(at(i), at(i + 1));
  }
  resetToSidelineEntry(true);
}

void SelfLocator::addHypothesis(const Eigen::Vector3d& mean, const Eigen::Matrix3d& cov, double score) {
  Hypothesis h;
  h.mean = mean;
  h.mean.z() = normalizeAngle(h.mean.z());
  h.cov = cov;
  h.score = score;
  h.id = nextId_++;
  hyps_.push_back(h);
}

void SelfLocator::startOver(const std::vector<Eigen::Vector3d>& means, const Eigen::Vector3d& sigmas, double xMin,
                            double xMax) {
  hyps_.clear();
  clusters_.clear();
  const Vec3 s = sigmas.cwiseAbs().cwiseMax(1e-4);
  for (const auto& m : means) {
    addHypothesis(m, s.cwiseProduct(s).asDiagonal(), 0.5);
    hyps_.back().xMin = xMin;
    hyps_.back().xMax = xMax;
  }
  selectedId_ = hyps_.front().id;
  lastGood_ = hyps_.front().mean;
}

void SelfLocator::resetToSidelineEntry(bool ownHalf) {
  const double hl = field_.halfLength(), hw = field_.halfWidth();
  std::vector<Vec3> means;
  for (double sy : {1.0, -1.0})
    for (double f : {1.0 / 6, 0.5, 5.0 / 6}) means.emplace_back((ownHalf ? -1 : 1) * f * hl, sy * hw, -sy * kPi / 2);
  const double inf = std::numeric_limits<double>::infinity(), m = params_.situationPriorMargin;
  startOver(means, params_.sidelineSigma, ownHalf ? -inf : -m, ownHalf ? m : inf);
}

void SelfLocator::resetToPenaltyReturn() {
  const double hl = field_.halfLength(), hw = field_.halfWidth();
  std::vector<Vec3> means;
  for (double sy : {1.0, -1.0}) means.emplace_back(-hl + field_.dims.penaltyCrossDistance, sy * hw, -sy * kPi / 2);
  startOver(means, params_.penaltyReturnSigma, -std::numeric_limits<double>::infinity(), params_.situationPriorMargin);
}

void SelfLocator::resetTo(const Pose2& pose, const Eigen::Vector3d& sigmas) {
  const Vec3 m = toVec(pose);
  if (!m.allFinite() || !sigmas.allFinite()) {
    ++stats_.skippedResets;
    return;
  }
  startOver({m}, sigmas, -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity());
}

RobotPose SelfLocator::update(const LocalizationInput& input) {
  applyOdometry(input.odometryDelta);
  for (const auto& p : input.percepts) applyPercepts(p, input.gyroZ);
  return estimate();
}

bool SelfLocator::applyOdometry(const Pose2& d) {
  if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.theta) ||
      std::hypot(d.x, d.y) > params_.maxOdometryStep || std::abs(d.theta) > params_.maxOdometryTurn) {
    ++stats_.skippedOdometry;
    return false;
  }
  const double dist = std::hypot(d.x, d.y), turn = std::abs(d.theta);
  const double st = params_.odomTransFloor + params_.odomTransPerMetre * dist + params_.odomTransPerRad * turn;
  const double sr = params_.odomRotFloor + params_.odomRotPerRad * turn + params_.odomRotPerMetre * dist;
  const double maxVar = 4 * field_.dims.length * field_.dims.length;
  for (auto& h : hyps_) {
    const double th = h.mean.z(), c = std::cos(th), s = std::sin(th);
    Mat3 F = Mat3::Identity();
    F(0, 2) = -s * d.x - c * d.y;
    F(1, 2) = c * d.x - s * d.y;
    h.mean.x() += c * d.x - s * d.y;
    h.mean.y() += s * d.x + c * d.y;
    h.mean.z() = normalizeAngle(th + d.theta);
    Mat3 Q = Mat3::Zero();
    Q(0, 0) = Q(1, 1) = st * st;  // isotropic in xy: no rotation needed
    Q(2, 2) = sr * sr;
    h.cov = sanitised(F * h.cov * F.transpose() + Q, maxVar);
  }
  return true;
}

double SelfLocator::expectedLineLength(const Eigen::Vector3d& pose, const std::vector<Eigen::Vector2d>& view,
                                       double* circle) const {
  if (view.size() < 3) return 0;
  const PoseFrame frame(pose);
  double sum = 0, arc = 0;
  for (const auto& l : field_.lines) sum += lengthInside(frame.toRobot(l.from), frame.toRobot(l.to), view);
  for (const auto& [a, b] : circleChords_) arc += lengthInside(frame.toRobot(a), frame.toRobot(b), view);
  if (circle) *circle = arc;
  return sum + arc;
}

bool SelfLocator::updateHypothesis(Hypothesis& h, const Elements& els, double& fit, int& used,
                                   double& matchedLength) const {
  const Associator as(field_, params_);
  bool circleFits = false;
  double sum = 0;
  used = 0;
  matchedLength = 0;
  const double maxVar = 4 * field_.dims.length * field_.dims.length;
  for (const auto& e : els) {
    ++used;
    Associator::Match m;
    if (!as.associate(e, h.mean, h.cov, m)) continue;
    if (e.kind == Element::Kind::Line) matchedLength += e.length;
    circleFits = circleFits || e.kind == Element::Kind::Circle;
    const Mat2 R = as.noise(e);
    // Fit: 1 inside the percept's own 2-sigma ellipse (86 % of right associations), fading out beyond.
    const double q = m.r.dot(R.ldlt().solve(m.r));
    sum += std::exp(-0.5 * std::clamp(q - 4.0, 0.0, 50.0));
    // EKF update (Joseph form).
    const Eigen::Matrix<double, 3, 2> K = h.cov * m.h.transpose() * m.s.inverse();
    const Vec3 mean = h.mean + K * m.r;
    const Mat3 IKH = Mat3::Identity() - K * m.h;
    const Mat3 cov = IKH * h.cov * IKH.transpose() + K * R * K.transpose();
    if (!mean.allFinite() || !cov.allFinite()) continue;
    h.mean = mean;
    h.mean.z() = normalizeAngle(h.mean.z());
    h.cov = sanitised(cov, maxVar);
  }
  fit = used > 0 ? sum / used : 0;
  return circleFits;
}

// A candidate is verified when at least candidateMinSupport of the image's percepts (and
// candidateMinPercepts of them) fit the field there; stops as soon as too many did not.
bool SelfLocator::supports(const Eigen::Vector3d& pose, const Elements& els) const {
  const Associator as(field_, params_);
  const int total = static_cast<int>(els.size());
  const int allowedMisses = static_cast<int>(std::floor((1 - params_.candidateMinSupport) * total + 1e-9));
  // A candidate is right to within its features' noise; allow a little in the pose.
  Mat3 P = Mat3::Zero();
  P(0, 0) = P(1, 1) = 0.05 * 0.05;
  P(2, 2) = 0.03 * 0.03;
  int matched = 0, missed = 0;
  for (const auto& e : els) {
    Associator::Match m;
    if (as.associate(e, pose, P, m)) {
      ++matched;
    } else if (++missed > allowedMisses) {
      return false;
    }
  }
  return matched >= params_.candidateMinPercepts;
}

std::vector<Pose2> SelfLocator::featureCandidates(const FieldPercepts& percepts) const {
  int skipped = 0;
  return candidatesFrom(percepts, elementsOf(percepts, params_, skipped));
}

std::vector<Pose2> SelfLocator::candidatesFrom(const FieldPercepts& percepts, const Elements& els) const {
  std::vector<Pose2> raw;
  const double hl = field_.halfLength();
  for (const auto& e : els) {
    // Centre circle + halfway line: the line passes through the circle's centre.
    if (e.kind == Element::Kind::Circle) {
      for (const auto& l : els) {
        if (l.kind != Element::Kind::Line || l.length < 0.3) continue;
        const Vec2 n(-l.u.y(), l.u.x());
        if (std::abs(n.dot(e.p - l.p)) > 0.25) continue;
        // The halfway line runs along field y.
        raw.push_back(poseFrom(kPi / 2 - angleOf(l.u), field_.centerCircleCenter, e.p));
      }
    }
    // Penalty mark + penalty-area front line, (penaltyAreaLength - penaltyCrossDistance) away.
    if (e.kind == Element::Kind::PenaltyMark) {
      const double want = field_.dims.penaltyAreaLength - field_.dims.penaltyCrossDistance;
      for (const auto& l : els) {
        if (l.kind != Element::Kind::Line || l.length < 0.3) continue;
        const Vec2 n(-l.u.y(), l.u.x());
        const double dist = n.dot(e.p - l.p);
        if (std::abs(std::abs(dist) - want) > 0.15) continue;
        const Vec2 w = dist * n;  // from the line to the mark; in the field -x for the own half
        raw.push_back(poseFrom(kPi - angleOf(w), Vec2(-hl + field_.dims.penaltyCrossDistance, 0), e.p));
      }
    }
  }
  // A typed corner with its orientation (from its two lines), matched against every field
  // corner of its type; only an unambiguous one (after verification) counts.
  std::vector<Pose2> cornerRaw;
  for (const auto& x : percepts.lines.intersections) {
    if (x.type == LinesPercept::Intersection::Type::X || !finite2(x.position)) continue;
    const auto& lines = percepts.lines.lines;
    if (x.line1 < 0 || x.line2 < 0 || x.line1 >= static_cast<int>(lines.size()) ||
        x.line2 >= static_cast<int>(lines.size()) || x.line1 == x.line2)
      continue;
    // Each line leaves the corner on one side (an arm) or passes through it (a bar).
    struct Arm {
      Vec2 dir;
      bool bar;
    };
    auto armOf = [&](const LinesPercept::Line& l, Arm& a) {
      if (!finite2(l.from) || !finite2(l.to)) return false;
      const Vec2 d = l.to - l.from;
      const double len = d.norm();
      if (len < 0.2) return false;
      const Vec2 u = d / len;
      const double sf = u.dot(l.from - x.position), st = u.dot(l.to - x.position);
      const double margin = 0.15;
      if (sf >= -margin && st > margin) a = {u, false};
      else if (st <= margin && sf < -margin) a = {-u, false};
      else a = {u, true};
      return true;
    };
    Arm a1, a2;
    if (!armOf(lines[x.line1], a1) || !armOf(lines[x.line2], a2)) continue;
    const bool isL = x.type == LinesPercept::Intersection::Type::L;
    if (isL && (a1.bar || a2.bar)) continue;
    // Robot-frame reference direction: for an L the first arm (with its handedness), for a T the stem.
    Vec2 ref;
    double handed = 0;
    if (isL) {
      ref = a1.dir;
      handed = a1.dir.x() * a2.dir.y() - a1.dir.y() * a2.dir.x();
    } else {
      if (a1.bar == a2.bar) continue;  // the stem cannot be told from the bar
      ref = a1.bar ? a2.dir : a1.dir;
    }
    for (const auto& c : corners_) {
      if (c.type != toFieldType(x.type)) continue;
      if (isL) {
        if (c.arms.size() != 2) continue;
        for (int k = 0; k < 2; ++k) {
          const Vec2 b1 = c.arms[k], b2 = c.arms[1 - k];
          const double hb = b1.x() * b2.y() - b1.y() * b2.x();
          if (hb * handed <= 0) continue;
          cornerRaw.push_back(poseFrom(angleOf(b1) - angleOf(ref), c.position, x.position));
        }
      } else {
        // The stem is the arm whose opposite is no arm.
        for (const auto& b : c.arms) {
          bool opposite = false;
          for (const auto& o : c.arms) opposite = opposite || o.dot(b) < -0.99;
          if (!opposite) cornerRaw.push_back(poseFrom(angleOf(b) - angleOf(ref), c.position, x.position));
        }
      }
    }
  }

  // The goal box seen from the side: its short line is one of the goal boxes' side lines, in
  // either direction; the long lines beside it decide which (verification, unambiguous only).
  std::vector<Pose2> boxRaw;
  const auto& gb = percepts.lines.goalBoxSide;
  const int nLines = static_cast<int>(percepts.lines.lines.size());
  if (gb.found && gb.shortLine >= 0 && gb.shortLine < nLines) {
    const auto& l = percepts.lines.lines[gb.shortLine];
    if (finite2(l.from) && finite2(l.to) && (l.to - l.from).norm() > 0.2) {
      const Vec2 c = 0.5 * (l.from + l.to);
      const double a = angleOf(l.to - l.from);
      for (const auto& m : field_.lines) {
        if (m.name.find("goal_box_left") == std::string::npos && m.name.find("goal_box_right") == std::string::npos)
          continue;
        const Vec2 mc = 0.5 * (m.from + m.to);
        const double ma = angleOf(m.to - m.from);
        for (double flip : {0.0, kPi}) boxRaw.push_back(poseFrom(ma + flip - a, mc, c));
      }
    }
  }

  auto verified = [&](const Pose2& p) { return supports(toVec(p), els); };
  auto same = [](const Pose2& a, const Pose2& b) {
    auto close = [](const Pose2& p, const Pose2& q) {
      return std::hypot(p.x - q.x, p.y - q.y) < 0.3 && std::abs(normalizeAngle(p.theta - q.theta)) < 0.2;
    };
    return close(a, b) || close(a, mirror(b));
  };
  auto addUnique = [&](std::vector<Pose2>& list, const Pose2& p) {
    for (const auto& q : list)
      if (same(p, q)) return;
    list.push_back(p);
  };

  std::vector<Pose2> out;
  for (const auto& p : raw)
    if (verified(p)) addUnique(out, p);
  std::vector<Pose2> corners;
  for (const auto& p : cornerRaw)
    if (verified(p)) addUnique(corners, p);
  if (corners.size() == 1) addUnique(out, corners.front());
  std::vector<Pose2> boxes;
  for (const auto& p : boxRaw)
    if (verified(p)) addUnique(boxes, p);
  if (boxes.size() == 1) addUnique(out, boxes.front());
  return out;
}

void SelfLocator::addCandidate(const Pose2& candidate, double time) {
  // Of the two mirror images, the one nearer the filter's hypotheses (all of them: while the
  // game situation still leaves several, the selected one may be the wrong one, and its
  // nearer image the mirrored truth).
  auto distance = [&](const Pose2& p) {
    auto to = [&](const Vec3& ref) {
      return std::hypot(p.x - ref.x(), p.y - ref.y()) +
             params_.mirrorAngleWeight * std::abs(normalizeAngle(p.theta - ref.z()));
    };
    double d = to(lastGood_);
    for (const auto& h : hyps_) d = std::min(d, to(h.mean));
    return d;
  };
  const Pose2 m = mirror(candidate);
  const Pose2 c = distance(m) < distance(candidate) ? m : candidate;
  ++stats_.candidates;

  Cluster* hit = nullptr;
  for (auto& cl : clusters_)
    if (std::hypot(cl.mean.x() - c.x, cl.mean.y() - c.y) < params_.clusterDistance &&
        std::abs(normalizeAngle(cl.mean.z() - c.theta)) < params_.clusterAngle) {
      hit = &cl;
      break;
    }
  if (hit) {
    ++hit->count;
    const double w = 1.0 / hit->count;
    hit->mean.x() += w * (c.x - hit->mean.x());
    hit->mean.y() += w * (c.y - hit->mean.y());
    hit->mean.z() = normalizeAngle(hit->mean.z() + w * normalizeAngle(c.theta - hit->mean.z()));
    hit->lastTime = time;
  } else {
    if (static_cast<int>(clusters_.size()) >= params_.maxClusters) {
      auto oldest = std::min_element(clusters_.begin(), clusters_.end(),
                                     [](const Cluster& a, const Cluster& b2) { return a.lastTime < b2.lastTime; });
      clusters_.erase(oldest);
    }
    clusters_.push_back({toVec(c), 1, time});
    hit = &clusters_.back();
  }
  if (hit->count < params_.clusterMinObservations) return;
  for (const auto& h : hyps_)
    if (std::hypot(h.mean.x() - hit->mean.x(), h.mean.y() - hit->mean.y()) < params_.resetDistance &&
        std::abs(normalizeAngle(h.mean.z() - hit->mean.z())) < params_.resetAngle)
      return;  // a hypothesis explains it; scores decide
  Mat3 cov = Mat3::Zero();
  cov(0, 0) = cov(1, 1) = 0.15 * 0.15;
  cov(2, 2) = 0.1 * 0.1;
  // Make room: the worst hypothesis goes when the list is full.
  if (static_cast<int>(hyps_.size()) >= params_.maxHypotheses) {
    auto worst = std::min_element(hyps_.begin(), hyps_.end(), [&](const Hypothesis& a, const Hypothesis& b2) {
      if ((a.id == selectedId_) != (b2.id == selectedId_)) return b2.id == selectedId_;
      return a.score < b2.score;
    });
    hyps_.erase(worst);
  }
  addHypothesis(hit->mean, cov, params_.resetScore);
  ++stats_.resets;
  clusters_.erase(clusters_.begin() + (hit - clusters_.data()));
}

void SelfLocator::applyPercepts(const FieldPercepts& percepts, double gyroZ) {
  if (!std::isfinite(percepts.time)) {
    ++stats_.skippedSets;
    return;
  }
  int skipped = 0;
  const Elements els = elementsOf(percepts, params_, skipped);
  stats_.skippedPercepts += skipped;
  time_ = std::max(time_, percepts.time);
  for (auto& h : hyps_) {
    // What this hypothesis says the image should show, before the image moves it.
    double arc = 0;
    const double expected = expectedLineLength(h.mean, percepts.view, &arc);
    double fit = 0, matched = 0;
    int used = 0;
    const bool circleFits = updateHypothesis(h, els, fit, used, matched);
    ++h.age;
    // Straight lines by their length; the centre circle (its arcs are not matched as straight
    // lines) as a whole: much of its arc in view and no circle that fits, and the image fits
    // no better than negativeMissedCircle.
    double seen = 1;
    const double straight = expected - arc;
    if (straight >= params_.negativeMinExpected)
      seen = std::clamp(matched / (params_.negativeDetectRate * straight), 0.0, 1.0);
    if (arc >= params_.negativeMinArc && !circleFits) seen = std::min(seen, params_.negativeMissedCircle);
    if (seen < 1) {
      ++stats_.negativeImages;
      fit = (used > 0 ? fit : 1.0) * seen;
      used = std::max(used, 1);
    }
    if (used > 0) h.score += params_.scoreRate * (fit - h.score);
  }
  hyps_.erase(std::remove_if(hyps_.begin(), hyps_.end(), [](const Hypothesis& h) { return !finite(h); }),
              hyps_.end());
  const std::size_t before = hyps_.size();
  hyps_.erase(std::remove_if(hyps_.begin(), hyps_.end(),
                             [&](const Hypothesis& h) {
                               return h.age < params_.situationPriorImages &&
                                      (h.mean.x() < h.xMin || h.mean.x() > h.xMax);
                             }),
              hyps_.end());
  stats_.priorViolations += static_cast<int>(before - hyps_.size());
  const std::size_t onField = hyps_.size();
  const double xLimit = field_.halfLength() + params_.offFieldMargin, yLimit = field_.halfWidth() + params_.offFieldMargin;
  hyps_.erase(std::remove_if(hyps_.begin(), hyps_.end(),
                             [&](const Hypothesis& h) { return std::abs(h.mean.x()) > xLimit || std::abs(h.mean.y()) > yLimit; }),
              hyps_.end());
  stats_.offField += static_cast<int>(onField - hyps_.size());
  reinitialiseIfEmpty();

  // Sensor resetting.
  if (std::isfinite(gyroZ) && std::abs(gyroZ) <= params_.maxGyroForFeatures)
    for (const auto& c : candidatesFrom(percepts, els)) addCandidate(c, time_);
  clusters_.erase(std::remove_if(clusters_.begin(), clusters_.end(),
                                 [&](const Cluster& c) { return c.lastTime < time_ - params_.clusterLifetime; }),
                  clusters_.end());
  manageHypotheses();
}

void SelfLocator::manageHypotheses() {
  // The game situation's prior, also between two of its hypotheses that became each other's
  // mirror image (both fit every percept): the one deeper inside the situation's half stays.
  auto young = [&](const Hypothesis& h) {
    return h.age < params_.situationPriorImages && (std::isfinite(h.xMax) || std::isfinite(h.xMin));
  };
  auto outside = [](const Hypothesis& h) { return std::max(h.mean.x() - h.xMax, h.xMin - h.mean.x()); };
  for (std::size_t i = 0; i < hyps_.size(); ++i)
    for (std::size_t j = i + 1; j < hyps_.size(); ++j) {
      if (!young(hyps_[i]) || !young(hyps_[j])) continue;
      const Pose2 m = mirror(toPose(hyps_[i].mean));
      const Vec3& b = hyps_[j].mean;
      if (std::hypot(m.x - b.x(), m.y - b.y()) > params_.situationMirrorDistance ||
          std::abs(normalizeAngle(m.theta - b.z())) > params_.situationMirrorAngle)
        continue;
      const std::size_t drop = outside(hyps_[i]) > outside(hyps_[j]) ? i : j;
      hyps_[drop].age = -1;  // marked
    }
  const std::size_t before = hyps_.size();
  hyps_.erase(std::remove_if(hyps_.begin(), hyps_.end(), [](const Hypothesis& h) { return h.age < 0; }), hyps_.end());
  stats_.priorViolations += static_cast<int>(before - hyps_.size());

  // Merge: of two hypotheses about the same pose, the better scored stays.
  for (std::size_t i = 0; i < hyps_.size(); ++i)
    for (std::size_t j = i + 1; j < hyps_.size();) {
      const Vec3 d = hyps_[i].mean - hyps_[j].mean;
      if (std::hypot(d.x(), d.y()) < params_.mergeDistance && std::abs(normalizeAngle(d.z())) < params_.mergeAngle) {
        const bool keepJ = hyps_[j].score > hyps_[i].score;
        if (keepJ) std::swap(hyps_[i], hyps_[j]);
        if (hyps_[j].id == selectedId_) selectedId_ = hyps_[i].id;
        hyps_.erase(hyps_.begin() + static_cast<std::ptrdiff_t>(j));
      } else {
        ++j;
      }
    }
  if (hyps_.empty()) return;
  double top = -1;
  for (const auto& h : hyps_) top = std::max(top, h.score);
  hyps_.erase(std::remove_if(hyps_.begin(), hyps_.end(),
                             [&](const Hypothesis& h) {
                               return h.age >= params_.pruneMinAge && h.score < top - params_.pruneMargin &&
                                      h.id != selectedId_;
                             }),
              hyps_.end());
  std::stable_sort(hyps_.begin(), hyps_.end(), [](const Hypothesis& a, const Hypothesis& b) { return a.score > b.score; });
  while (static_cast<int>(hyps_.size()) > params_.maxHypotheses) hyps_.pop_back();
  // Selection with hysteresis.
  const Hypothesis* sel = nullptr;
  for (const auto& h : hyps_)
    if (h.id == selectedId_) sel = &h;
  // Hysteresis once the selected hypothesis has proved itself; among young ones, the best now.
  const double margin = sel && sel->age >= params_.pruneMinAge ? params_.switchMargin : 0.0;
  if (!sel || hyps_.front().score > sel->score + margin) sel = &hyps_.front();
  selectedId_ = sel->id;
  lastGood_ = sel->mean;
}

void SelfLocator::reinitialiseIfEmpty() {
  if (!hyps_.empty()) return;
  ++stats_.reinitialisations;
  Mat3 cov = Mat3::Zero();
  cov(0, 0) = cov(1, 1) = 1.0;
  cov(2, 2) = 0.5 * 0.5;
  addHypothesis(lastGood_.allFinite() ? lastGood_ : Vec3::Zero(), cov, 0.2);
  selectedId_ = hyps_.front().id;
}

const SelfLocator::Hypothesis* SelfLocator::best() const {
  for (const auto& h : hyps_)
    if (h.id == selectedId_) return &h;
  return hyps_.empty() ? nullptr : &hyps_.front();
}

RobotPose SelfLocator::estimate() const {
  RobotPose out;
  const Hypothesis* b = best();
  if (!b) {
    out.pose = toPose(lastGood_);
    out.covariance = Mat3::Identity();
    return out;
  }
  out.pose = toPose(b->mean);
  out.covariance = b->cov;
  out.quality = std::clamp(b->score, 0.0, 1.0);
  out.hypotheses = static_cast<int>(hyps_.size());
  out.valid = out.quality >= params_.validQuality && out.sigmaTranslation() <= params_.validSigmaTranslation &&
              out.sigmaRotation() <= params_.validSigmaRotation;
  return out;
}

}  // namespace nao
