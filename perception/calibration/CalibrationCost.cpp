#include "perception/calibration/CalibrationCost.h"

#include <algorithm>
#include <cmath>

#include "robot/Error.h"

namespace nao::calibration {
namespace {

constexpr double kRadToDeg = 180 / std::numbers::pi;

// A ground line in normal form n . p = c (|n| = 1).
struct GroundLine {
  Eigen::Vector2d n;
  double c;
};

bool projectEdge(const CameraMatrix& cm, const ImageLine& edge, GroundLine& out) {
  const auto a = cm.pixelToGround(edge.from);
  const auto b = cm.pixelToGround(edge.to);
  if (!a || !b) return false;
  const Eigen::Vector2d d = *b - *a;
  const double len = d.norm();
  if (!(len > 1e-9)) return false;
  out.n = Eigen::Vector2d(-d.y(), d.x()) / len;
  out.c = out.n.dot(*a);
  return true;
}

// The bisector of two nearly parallel ground lines: the points equally far from both. For the
// two paint edges of a line that is the line's centre.
bool centreLine(const CameraMatrix& cm, const LineMeasurement& m, Eigen::ParametrizedLine<double, 2>& out) {
  GroundLine a, b;
  if (!projectEdge(cm, m.edgeA, a) || !projectEdge(cm, m.edgeB, b)) return false;
  if (a.n.dot(b.n) < 0) {
    b.n = -b.n;
    b.c = -b.c;
  }
  Eigen::Vector2d n = a.n + b.n;
  const double norm = n.norm();
  n /= norm;
  const double c = (a.c + b.c) / norm;
  out = Eigen::ParametrizedLine<double, 2>(c * n, Eigen::Vector2d(-n.y(), n.x()));
  return true;
}

Eigen::Vector2d intersect(const Eigen::ParametrizedLine<double, 2>& a, const Eigen::ParametrizedLine<double, 2>& b) {
  // a.o + s a.d = b.o + t b.d
  const Eigen::Vector2d& d1 = a.direction();
  const Eigen::Vector2d& d2 = b.direction();
  const double det = d1.x() * (-d2.y()) - d1.y() * (-d2.x());
  const Eigen::Vector2d r = b.origin() - a.origin();
  const double s = (r.x() * (-d2.y()) - r.y() * (-d2.x())) / det;
  return a.origin() + s * d1;
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

CostOptions CostOptions::forField(const FieldDimensions& field) {
  if (!field.hasGoalBox)
    throw Error("field dimensions", "the calibration needs a goal box (field.goalBoxAreaLength/Width)");
  CostOptions o;
  o.goalBoxDepth = field.goalBoxAreaLength;
  return o;
}

CalibrationCost::CalibrationCost(std::vector<CalibrationSample> samples, const CostOptions& options)
    : samples_(std::move(samples)), options_(options) {
  if (samples_.empty()) throw Error("calibration", "no samples to calibrate with");
  if (!(options_.goalBoxDepth > 0) || !(options_.angleSigma > 0) || !(options_.depthSigma > 0))
    throw Error("calibration", "goal box depth and residual sigmas must be positive");
  robotToTorso_.reserve(samples_.size());
  for (const auto& s : samples_) robotToTorso_.push_back(robotToTorso(s.joints, s.imuAngle.x(), s.imuAngle.y()));
  if (options_.paintTurns && !(options_.turnPriorSigma > 0)) throw Error("calibration", "the turns' prior sigma must be positive");
  if (options_.paintDepth && !(options_.depthPriorSigma > 0)) throw Error("calibration", "the depth's prior sigma must be positive");
  // Which long line meets the short line further left in the image (the image's midlines).
  for (const auto& s : samples_) {
    const ImageLine sc = s.lines[ShortLine].centre(), l1 = s.lines[LongLine1].centre(), l2 = s.lines[LongLine2].centre();
    auto meet = [&](const ImageLine& l) {
      const Eigen::ParametrizedLine<double, 2> a(sc.from, (sc.to - sc.from).normalized()), b(l.from, (l.to - l.from).normalized());
      return intersect(a, b);
    };
    longLine1IsLeft_.push_back(meet(l1).x() < meet(l2).x());
  }
}

bool CalibrationCost::groundLines(const Params& x, int sample,
                                  std::array<Eigen::ParametrizedLine<double, 2>, 3>& out) const {
  const CalibrationSample& s = samples_[sample];
  CameraMatrix cm;
  if (s.cameraPose) {
    const double roll = s.camera == CameraId::Top ? x[2] : x[4], pitch = s.camera == CameraId::Top ? x[3] : x[5];
    cm.pose = *s.cameraPose * Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()) *
              Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY());
    cm.intrinsics = s.intrinsics;
  } else {
    cm = computeCameraMatrix(s.joints, robotToTorso_[sample], s.camera, CameraCalibration::fromArray(x), s.intrinsics);
  }
  for (int l = 0; l < 3; ++l)
    if (!centreLine(cm, s.lines[l], out[l])) return false;
  return true;
}

double CalibrationCost::turnOf(const double* x, int sample, int role) const {
  if (!options_.paintTurns || role == ShortLine) return 0;
  const bool left = (role == LongLine1) == static_cast<bool>(longLine1IsLeft_[sample]);
  return left ? x[6] : x[7];
}

// The sample's right angles and parallelism as sines (in the *Deg fields: the public overloads
// turn them into degrees) and its depth error, with the long lines turned back by the paint's
// turns in x; out.projected false when a line does not reach the ground.
void CalibrationCost::sampleResiduals(const double* x, int sample, SampleResiduals& out) const {
  const Params p = {x[0], x[1], x[2], x[3], x[4], x[5]};
  std::array<Eigen::ParametrizedLine<double, 2>, 3> g;
  if (!groundLines(p, sample, g)) {
    out.projected = false;
    return;
  }
  // A line painted turned by t (counterclockwise about its junction) is seen turned by t: the
  // rules' direction is the seen one turned back. The junction stays where it is.
  auto unturned = [&](int role) {
    return Eigen::Vector2d(Eigen::Rotation2Dd(-turnOf(x, sample, role)) * g[role].direction());
  };
  const Eigen::Vector2d& ds = g[ShortLine].direction();
  const Eigen::Vector2d d1 = unturned(LongLine1), d2 = unturned(LongLine2);
  // Sines here; degrees for people in the public overloads.
  out.angle1Deg = ds.dot(d1);
  out.angle2Deg = ds.dot(d2);
  out.depthErrorM = (intersect(g[ShortLine], g[LongLine1]) - intersect(g[ShortLine], g[LongLine2])).norm() -
                    options_.goalBoxDepth - depthErrorOf(x);
  // The sign of a direction is arbitrary: sin of the angle between the lines, made independent of it.
  out.parallelDeg = cross(d1, d2) * (d1.dot(d2) < 0 ? -1 : 1);
}

void CalibrationCost::residuals(const double* x, double* r) const {
  const int k = residualsPerSample();
  for (int i = 0; i < static_cast<int>(samples_.size()); ++i) {
    double* ri = r + k * i;
    SampleResiduals s;
    sampleResiduals(x, i, s);
    if (!s.projected) {
      for (int j = 0; j < k; ++j) ri[j] = kUnprojectable;
      continue;
    }
    const double w = weights_.empty() ? 1.0 : weights_[i];
    ri[0] = w * s.angle1Deg / options_.angleSigma;
    ri[1] = w * s.angle2Deg / options_.angleSigma;
    ri[2] = w * s.depthErrorM / options_.depthSigma;
    if (options_.parallelism) ri[3] = w * s.parallelDeg / options_.angleSigma;
  }
  // The paint's priors.
  double* prior = r + k * samples_.size();
  if (options_.paintTurns) *prior++ = x[6] / options_.turnPriorSigma, *prior++ = x[7] / options_.turnPriorSigma;
  if (options_.paintDepth) *prior++ = depthErrorOf(x) / options_.depthPriorSigma;
}

void CalibrationCost::setSampleWeights(std::vector<double> weights) {
  if (!weights.empty() && weights.size() != samples_.size())
    throw Error("calibration", "one weight per sample expected");
  weights_ = std::move(weights);
}

Eigen::VectorXd CalibrationCost::parameters(const Params& offsets, const std::vector<double>& paint) const {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(parameterCount());
  for (int k = 0; k < 6; ++k) x[k] = offsets[k];
  if (static_cast<int>(paint.size()) == paintCount())
    for (std::size_t k = 0; k < paint.size(); ++k) x[6 + static_cast<int>(k)] = paint[k];
  return x;
}

Eigen::VectorXd CalibrationCost::residuals(const Params& x) const { return residualsWithPaint(parameters(x)); }

Eigen::VectorXd CalibrationCost::residualsWithPaint(const Eigen::VectorXd& x) const {
  if (x.size() != parameterCount()) throw Error("calibration", "parameter vector of the wrong size");
  Eigen::VectorXd r(residualCount());
  residuals(x.data(), r.data());
  return r;
}

double CalibrationCost::cost(const Params& x) const { return 0.5 * residuals(x).squaredNorm(); }

SampleResiduals CalibrationCost::sampleResiduals(const Params& x, int sample) const {
  return sampleResidualsWithPaint(parameters(x), sample);
}

SampleResiduals CalibrationCost::sampleResidualsWithPaint(const Eigen::VectorXd& x, int sample) const {
  if (x.size() != parameterCount()) throw Error("calibration", "parameter vector of the wrong size");
  SampleResiduals out;
  sampleResiduals(x.data(), sample, out);
  if (!out.projected) return out;
  auto deg = [](double sine) { return std::asin(std::clamp(sine, -1.0, 1.0)) * kRadToDeg; };
  out.angle1Deg = deg(out.angle1Deg);
  out.angle2Deg = deg(out.angle2Deg);
  out.parallelDeg = deg(out.parallelDeg);
  return out;
}

ImageLine LineMeasurement::centre() const {
  // Pair the ends so that the midline does not cross itself.
  const bool flip = (edgeA.to - edgeA.from).dot(edgeB.to - edgeB.from) < 0;
  const Eigen::Vector2d& bFrom = flip ? edgeB.to : edgeB.from;
  const Eigen::Vector2d& bTo = flip ? edgeB.from : edgeB.to;
  return {(edgeA.from + bFrom) / 2, (edgeA.to + bTo) / 2};
}

}  // namespace nao::calibration
