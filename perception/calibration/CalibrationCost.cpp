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

void CalibrationCost::residuals(const double* x, double* r) const {
  const Params p = {x[0], x[1], x[2], x[3], x[4], x[5]};
  const int k = residualsPerSample();
  for (int i = 0; i < static_cast<int>(samples_.size()); ++i) {
    double* ri = r + k * i;
    std::array<Eigen::ParametrizedLine<double, 2>, 3> g;
    if (!groundLines(p, i, g)) {
      for (int j = 0; j < k; ++j) ri[j] = kUnprojectable;
      continue;
    }
    const double w = weights_.empty() ? 1.0 : weights_[i];
    const Eigen::Vector2d& ds = g[ShortLine].direction();
    ri[0] = ds.dot(g[LongLine1].direction()) / options_.angleSigma;
    ri[1] = ds.dot(g[LongLine2].direction()) / options_.angleSigma;
    const Eigen::Vector2d j1 = intersect(g[ShortLine], g[LongLine1]);
    const Eigen::Vector2d j2 = intersect(g[ShortLine], g[LongLine2]);
    ri[2] = ((j1 - j2).norm() - options_.goalBoxDepth) / options_.depthSigma;
    if (options_.parallelism) {
      // The sign of a direction is arbitrary: sin of the angle between the lines, made
      // independent of it.
      const Eigen::Vector2d& d1 = g[LongLine1].direction();
      const Eigen::Vector2d& d2 = g[LongLine2].direction();
      ri[3] = cross(d1, d2) * (d1.dot(d2) < 0 ? -1 : 1) / options_.angleSigma;
    }
    for (int j = 0; j < k; ++j) ri[j] *= w;
  }
}

void CalibrationCost::setSampleWeights(std::vector<double> weights) {
  if (!weights.empty() && weights.size() != samples_.size())
    throw Error("calibration", "one weight per sample expected");
  weights_ = std::move(weights);
}

Eigen::VectorXd CalibrationCost::residuals(const Params& x) const {
  Eigen::VectorXd r(residualCount());
  residuals(x.data(), r.data());
  return r;
}

double CalibrationCost::cost(const Params& x) const { return 0.5 * residuals(x).squaredNorm(); }

SampleResiduals CalibrationCost::sampleResiduals(const Params& x, int sample) const {
  SampleResiduals out;
  std::array<Eigen::ParametrizedLine<double, 2>, 3> g;
  if (!groundLines(x, sample, g)) {
    out.projected = false;
    return out;
  }
  const Eigen::Vector2d& ds = g[ShortLine].direction();
  out.angle1Deg = std::asin(std::clamp(ds.dot(g[LongLine1].direction()), -1.0, 1.0)) * kRadToDeg;
  out.angle2Deg = std::asin(std::clamp(ds.dot(g[LongLine2].direction()), -1.0, 1.0)) * kRadToDeg;
  out.depthErrorM = (intersect(g[ShortLine], g[LongLine1]) - intersect(g[ShortLine], g[LongLine2])).norm() -
                    options_.goalBoxDepth;
  const Eigen::Vector2d& d1 = g[LongLine1].direction();
  const Eigen::Vector2d& d2 = g[LongLine2].direction();
  out.parallelDeg = std::asin(std::clamp(cross(d1, d2) * (d1.dot(d2) < 0 ? -1 : 1), -1.0, 1.0)) * kRadToDeg;
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
