#include "perception/vision/BallDetector.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "perception/vision/ColourTests.h"

namespace nao::vision {

Eigen::Matrix2d ballCovariance(const CameraMatrix& cm, const Eigen::Vector2d& centre, double radiusPx, double radius) {
  const double sigmaPx = std::max(0.5, 0.08 * radiusPx);
  Eigen::Matrix2d j;
  for (int axis = 0; axis < 2; ++axis) {
    Eigen::Vector2d d = Eigen::Vector2d::Zero();
    d[axis] = 0.5;
    const auto a = cm.pixelToGround(centre + d, radius), b = cm.pixelToGround(centre - d, radius);
    j.col(axis) = a && b ? Eigen::Vector2d(*a - *b) : Eigen::Vector2d(0.1, 0.1);
  }
  return sigmaPx * sigmaPx * j * j.transpose() + 1e-6 * Eigen::Matrix2d::Identity();
}

double expectedBallRadius(const CameraMatrix& cm, const Eigen::Vector2d& pixel, double radius) {
  const auto g = cm.pixelToGround(pixel, radius);
  if (!g) return 0;
  const Eigen::Vector3d centre(g->x(), g->y(), radius);
  const double dist = (centre - cm.pose.translation()).norm();
  if (dist <= radius) return 0;
  // The apparent radius of a sphere: f tan(asin(R / d)).
  return cm.intrinsics.fy * std::tan(std::asin(radius / dist));
}

namespace {

// Field here: the field's colour (FieldReference::isField), and clearly more saturated than
// the white point -- at least half the field's own chroma at that luminance. The ball's
// white, tinted green by the light the carpet throws onto it, is not field. Everything is
// compared squared, and the hue range as a sector between two unit vectors: the verifier
// asks this a few thousand times per image.
class FieldTest {
 public:
  explicit FieldTest(const FieldReference& field) : field_(field) {
    constexpr double kSlack = 0.08;  // FieldReference::isField's default
    const double lo = field.hueMin - kSlack, hi = field.hueMax + kSlack;
    sector_ = hi - lo < M_PI;
    loU_ = std::cos(lo), loV_ = std::sin(lo), hiU_ = std::cos(hi), hiV_ = std::sin(hi);
    const double minChroma = std::max(0.6 * field.satMin, 2.0);
    minChroma2_ = minChroma * minChroma;
    relSatPerY2_ = 0.25 * field.fieldRelSatPerY * field.fieldRelSatPerY;
    satMin2_ = field.satMin * field.satMin;
  }
  bool operator()(const PixelColour& c) const {
    if (!field_.valid) return false;
    const double du = c.u - 128, dv = c.v - 128;
    if (du * du + dv * dv < minChroma2_) return false;
    const double ru = du - field_.whiteU * c.y, rv = dv - field_.whiteV * c.y;
    if (ru * ru + rv * rv < std::min(relSatPerY2_ * c.y * c.y, satMin2_)) return false;
    if (!sector_) return field_.isField(c);
    return loU_ * dv - loV_ * du >= 0 && du * hiV_ - dv * hiU_ >= 0;
  }
  bool at(const CameraImage& img, const Eigen::Vector2d& p) const { return (*this)(sampleColour(img, p.x(), p.y())); }

 private:
  const FieldReference& field_;
  bool sector_ = false;
  double loU_ = 1, loV_ = 0, hiU_ = 1, hiV_ = 0, minChroma2_ = 0, relSatPerY2_ = 0, satMin2_ = 0;
};

// Unit vectors at 2 pi (k + phase) / n, k = 0..n-1, computed once.
template <int N, int PhaseTimes2>
const std::array<Eigen::Vector2d, N>& directions() {
  static const std::array<Eigen::Vector2d, N> dirs = [] {
    std::array<Eigen::Vector2d, N> d;
    for (int k = 0; k < N; ++k) {
      const double a = 2 * M_PI * (k + 0.5 * PhaseTimes2) / N;
      d[k] = Eigen::Vector2d(std::cos(a), std::sin(a));
    }
    return d;
  }();
  return dirs;
}

constexpr int kRays = 16;  // rays of the outline
const auto& rayDirs() { return directions<kRays, 0>(); }

struct Circle {
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  double r = 0;
};

// Algebraic (Kasa) circle fit.
bool fitCircle(const std::vector<Eigen::Vector2d>& pts, Circle& out) {
  if (pts.size() < 3) return false;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : pts) mean += p;
  mean /= static_cast<double>(pts.size());
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (const auto& p : pts) {
    const Eigen::Vector2d q = p - mean;
    const Eigen::Vector3d row(q.x(), q.y(), 1);
    a += row * row.transpose();
    b += row * -(q.squaredNorm());
  }
  if (std::abs(a.determinant()) < 1e-9) return false;
  const Eigen::Vector3d s = a.ldlt().solve(b);
  const Eigen::Vector2d c(-s(0) / 2, -s(1) / 2);
  const double r2 = c.squaredNorm() - s(2);
  if (!(r2 > 0)) return false;
  out.c = c + mean;
  out.r = std::sqrt(r2);
  return true;
}

// The circle through three points (false when they are nearly collinear).
bool circleThrough(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, Circle& out) {
  const double d = 2 * (a.x() * (b.y() - c.y()) + b.x() * (c.y() - a.y()) + c.x() * (a.y() - b.y()));
  if (std::abs(d) < 1e-6) return false;
  const double a2 = a.squaredNorm(), b2 = b.squaredNorm(), c2 = c.squaredNorm();
  out.c = Eigen::Vector2d((a2 * (b.y() - c.y()) + b2 * (c.y() - a.y()) + c2 * (a.y() - b.y())) / d,
                          (a2 * (c.x() - b.x()) + b2 * (a.x() - c.x()) + c2 * (b.x() - a.x())) / d);
  out.r = (out.c - a).norm();
  return true;
}

// The image direction of the world's up at a pixel (image -y for an upright camera).
Eigen::Vector2d imageUp(const CameraMatrix& cm, const Eigen::Vector2d& pixel, double height) {
  if (const auto g = cm.pixelToGround(pixel, height)) {
    const auto a = cm.project(Eigen::Vector3d(g->x(), g->y(), height));
    const auto b = cm.project(Eigen::Vector3d(g->x(), g->y(), height + 0.1));
    if (a && b && (*b - *a).norm() > 1e-6) return (*b - *a).normalized();
  }
  return Eigen::Vector2d(0, -1);
}

struct Outline {
  std::vector<Eigen::Vector2d> edges;
  int offImage = 0;  // rays that left the image first
};

// From `origin`, walks the rays up to maxLen and records where the field starts (more than a
// speck of it), placed to the pixel by bisection. Rays that leave the image or never reach
// the field are dropped.
Outline castRays(const CameraImage& img, const FieldTest& onField, const Eigen::Vector2d& origin, double maxLen) {
  Outline o;
  const double step = std::max(1.0, maxLen / 15);  // about a sixth of the expected radius
  for (const Eigen::Vector2d& d : rayDirs()) {
    double lastOff = 0;  // the last step not on the field
    for (double t = step; t <= maxLen; t += step) {
      const Eigen::Vector2d p = origin + t * d;
      if (!insideImage(img, p.x(), p.y(), 0.5)) {
        ++o.offImage;
        break;
      }
      if (!onField.at(img, p)) {
        lastOff = t;
        continue;
      }
      const Eigen::Vector2d q = origin + (t + std::max(1.0, 0.5 * step)) * d;
      if (insideImage(img, q.x(), q.y(), 0.5) && !onField.at(img, q)) continue;
      double lo = lastOff, hi = t;
      while (hi - lo > 0.75) {
        const double mid = 0.5 * (lo + hi);
        (onField.at(img, origin + mid * d) ? hi : lo) = mid;
      }
      o.edges.push_back(origin + 0.5 * (lo + hi) * d);
      break;
    }
  }
  return o;
}

// The outline where the field is not beside the ball (a foot, a line, a shadow): along each
// ray the outermost pixel as bright as the ball's white parts, provided darker pixels follow
// (a ray running on into other white paint is dropped).
Outline castBrightRays(const CameraImage& img, const Eigen::Vector2d& origin, double expectedR) {
  Outline o;
  // The ball's white level: bright samples near the origin.
  std::array<double, 48> ys{};
  int n = 0;
  for (double rr : {0.3, 0.6})
    for (const Eigen::Vector2d& d : directions<24, 0>()) {
      const Eigen::Vector2d p = origin + rr * expectedR * d;
      if (insideImage(img, p.x(), p.y(), 0.5)) ys[n++] = sampleLuminance(img, p.x(), p.y());
    }
  if (n < 12) return o;
  std::nth_element(ys.begin(), ys.begin() + n * 8 / 10, ys.begin() + n);
  const double level = 0.75 * ys[n * 8 / 10];
  const double step = std::max(0.75, expectedR / 12);
  for (const Eigen::Vector2d& d : rayDirs()) {
    double lastBright = -1;
    int darkAfter = 0;
    bool left = false;
    for (double t = 0.4 * expectedR; t <= 1.9 * expectedR; t += step) {
      const Eigen::Vector2d p = origin + t * d;
      if (!insideImage(img, p.x(), p.y(), 0.5)) {
        left = true;
        break;
      }
      if (sampleLuminance(img, p.x(), p.y()) >= level) {
        lastBright = t;
        darkAfter = 0;
      } else if (lastBright > 0 && ++darkAfter * step > 0.3 * expectedR) {
        break;
      }
    }
    if (left) {
      ++o.offImage;
      continue;
    }
    if (lastBright < 0 || darkAfter * step <= 0.3 * expectedR) continue;
    o.edges.push_back(origin + (lastBright + 0.5 * step) * d);
  }
  return o;
}

// A circle through the outline that most outline points agree with (a ball touching a line
// or lying in its shadow has outline points on those instead): circles through spread
// triples of points, the one with most points near it (ties: the radius nearest the
// expected one), refitted to those. The agreeing points must pin the circle down: no empty
// gap of 220 deg or more on the part of the circle inside the image (a ball cut by the image
// border shows only the arc inside).
bool robustFit(const CameraImage& img, const Outline& o, Circle& c, int& inliers, double expectedR) {
  const int n = static_cast<int>(o.edges.size());
  if (n < 5) return false;
  auto near = [](const Eigen::Vector2d& p, const Circle& h) {
    const double tol = std::max(1.5, 0.12 * h.r);
    const double d2 = (p - h.c).squaredNorm(), lo = std::max(0.0, h.r - tol), hi = h.r + tol;
    return d2 > lo * lo && d2 < hi * hi;
  };
  Circle best{};
  int bestCount = 0;
  double bestDev = 1e9;
  auto consider = [&](const Circle& h) {
    if (!(h.r > 0.5 * expectedR && h.r < 2 * expectedR)) return;
    int count = 0;
    for (const auto& p : o.edges) count += near(p, h);
    const double dev = std::abs(h.r - expectedR);
    if (count > bestCount || (count == bestCount && dev < bestDev)) best = h, bestCount = count, bestDev = dev;
  };
  Circle all;
  if (fitCircle(o.edges, all)) consider(all);
  for (int step : {n / 3, n / 4})
    for (int i = 0; i < n && step > 0; ++i) {
      Circle h;
      if (circleThrough(o.edges[i], o.edges[(i + step) % n], o.edges[(i + 2 * step) % n], h)) consider(h);
    }
  if (bestCount < 5) return false;
  std::vector<Eigen::Vector2d> keep;
  for (const auto& p : o.edges)
    if (near(p, best)) keep.push_back(p);
  c = best;
  if (keep.size() < 5 || !fitCircle(keep, c)) return false;
  inliers = static_cast<int>(keep.size());
  std::vector<double> angles;
  for (const auto& p : keep) angles.push_back(std::atan2(p.y() - c.c.y(), p.x() - c.c.x()));
  std::sort(angles.begin(), angles.end());
  auto seenArc = [&](double from, double to) {  // the part of (from, to) whose circle points are in the image
    const int steps = std::max(1, static_cast<int>((to - from) / (5 * M_PI / 180)));
    int in = 0;
    for (int k = 0; k < steps; ++k) {
      const double a = from + (k + 0.5) * (to - from) / steps;
      const Eigen::Vector2d p = c.c + c.r * Eigen::Vector2d(std::cos(a), std::sin(a));
      in += insideImage(img, p.x(), p.y());
    }
    return (to - from) * in / steps;
  };
  double gap = seenArc(angles.back(), angles.front() + 2 * M_PI);
  for (std::size_t i = 1; i < angles.size(); ++i) gap = std::max(gap, seenArc(angles[i - 1], angles[i]));
  return gap < 220 * M_PI / 180;
}

// Outline and circle from a seed inside the ball: rays to where the field starts, a robust
// circle through them, once more from its centre (when that is in the image); where that
// fails, the same with the outline of the bright parts. Most rays that stay in the image
// must end on the circle.
bool fitOutline(const CameraImage& img, const FieldTest& onField, const BallParams& params, BallCandidate& c,
                Circle& circle, bool keepOutline) {
  for (const bool bright : {false, true}) {
    Circle fit{c.seed, c.expectedRadius};
    int inliers = 0, offImage = 0;
    bool ok = false;
    Eigen::Vector2d origin = c.seed;
    for (int pass = 0; pass < 2; ++pass) {
      const Outline o = bright ? castBrightRays(img, origin, c.expectedRadius)
                               : castRays(img, onField, origin, 2.4 * std::max(fit.r, c.expectedRadius));
      if (keepOutline) c.outline = o.edges;
      Circle h = fit;
      int in = 0;
      if (!robustFit(img, o, h, in, c.expectedRadius)) break;
      ok = true, fit = h, inliers = in, offImage = o.offImage;
      if (!insideImage(img, fit.c.x(), fit.c.y(), 1.0)) break;
      origin = fit.c;
    }
    c.inliers = inliers, c.offImage = offImage;
    if (ok && inliers >= params.minOutline * (kRays - offImage)) {
      circle = fit;
      c.byBrightOutline = bright;
      return true;
    }
  }
  return false;
}

// Inside a circle: rings at fixed fractions of the radius (perRing samples each, alternate
// rings staggered) and the centre; samples off the image are left out.
struct Inside {
  int n = 0;
  double white = 0, dark = 0;  // the 90th and 10th percentiles of the luminance
  double contrast = 0;         // (white - dark) / white
  double darkRatio = 0;        // fraction below dark + 0.35 (white - dark)
  double pattern = 0;          // RMS of the rings' luminance after their mean and first harmonic, / white
  double fieldRatio = 0;       // field-coloured samples
  double relSat = 0;           // mean chroma about the white point
};

template <int PerRing>
Inside measureInside(const CameraImage& img, const FieldReference& field, const FieldTest& onField,
                     const Circle& circle) {
  Inside in;
  constexpr double kRings[] = {0.2, 0.45, 0.65, 0.82};
  std::array<double, 4 * PerRing + 1> ys{};
  int fieldCount = 0;
  double sat = 0, res2 = 0;
  int resN = 0;
  auto take = [&](const PixelColour& col) {
    ys[in.n++] = col.y;
    fieldCount += onField(col);
    sat += field.relSat(col);
  };
  if (insideImage(img, circle.c.x(), circle.c.y(), 0.5)) take(sampleColour(img, circle.c.x(), circle.c.y()));
  for (int ring = 0; ring < 4; ++ring) {
    // The ring's samples, and a least-squares fit of y = a + b cos + c sin to them: smooth
    // shading (a gradient across the ball, a highlight) is that; the black patches are not.
    const auto& dirs = ring % 2 ? directions<PerRing, 1>() : directions<PerRing, 0>();
    std::array<double, PerRing> y{};
    std::array<int, PerRing> idx{};
    int m = 0;
    for (int k = 0; k < PerRing; ++k) {
      const Eigen::Vector2d p = circle.c + kRings[ring] * circle.r * dirs[k];
      if (!insideImage(img, p.x(), p.y(), 0.5)) continue;
      const PixelColour col = sampleColour(img, p.x(), p.y());
      take(col);
      y[m] = col.y, idx[m] = k;
      ++m;
    }
    if (ring == 0 || m < 8) continue;
    Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for (int k = 0; k < m; ++k) {
      const Eigen::Vector3d row(1, dirs[idx[k]].x(), dirs[idx[k]].y());
      a += row * row.transpose();
      b += row * y[k];
    }
    const Eigen::Vector3d x = a.ldlt().solve(b);
    for (int k = 0; k < m; ++k) {
      const double e = y[k] - (x(0) + x(1) * dirs[idx[k]].x() + x(2) * dirs[idx[k]].y());
      res2 += e * e;
      ++resN;
    }
  }
  if (in.n == 0) return in;
  std::sort(ys.begin(), ys.begin() + in.n);
  in.white = ys[in.n * 9 / 10];
  in.dark = ys[in.n / 10];
  in.contrast = (in.white - in.dark) / std::max(1.0, in.white);
  const double split = in.dark + 0.35 * (in.white - in.dark);
  in.darkRatio = static_cast<double>(std::lower_bound(ys.begin(), ys.begin() + in.n, split) - ys.begin()) / in.n;
  in.pattern = resN ? std::sqrt(res2 / resN) / std::max(1.0, in.white) : 0;
  in.fieldRatio = static_cast<double>(fieldCount) / in.n;
  in.relSat = sat / in.n;
  return in;
}

// A ring at 1.4 r: how much of it is field, and the field's chroma there.
struct Around {
  int n = 0, field = 0;
  double relSat = 0;  // mean over the field samples
  double y = 0;       // median luminance
};

Around measureAround(const CameraImage& img, const FieldReference& field, const FieldTest& onField,
                     const Circle& circle) {
  Around ar;
  std::array<double, 16> ys{};
  for (const Eigen::Vector2d& d : directions<16, 0>()) {
    const Eigen::Vector2d p = circle.c + 1.4 * circle.r * d;
    if (!insideImage(img, p.x(), p.y(), 0.5)) continue;
    const PixelColour col = sampleColour(img, p.x(), p.y());
    ys[ar.n++] = col.y;
    if (onField(col)) ++ar.field, ar.relSat += field.relSat(col);
  }
  if (ar.field) ar.relSat /= ar.field;
  if (ar.n) {
    std::nth_element(ys.begin(), ys.begin() + ar.n / 2, ys.begin() + ar.n);
    ar.y = ys[ar.n / 2];
  }
  return ar;
}

// The fraction of the directions (of those in the image) in which the circle is a real
// border: the field starts just outside it, or the colour steps across it (from the ball's
// white or black to something else). A surface that carries on across the circle -- the
// rest of a robot's shoulder, a goal post above its foot -- does neither.
double outlineSupport(const CameraImage& img, const FieldTest& onField, const Circle& circle, double white) {
  const double step = std::max(0.12 * white, 8.0);
  const double margin = std::max(1.0, 0.25 * circle.r);
  const double rIn = std::max(0.5 * circle.r, circle.r - margin), rOut = circle.r + margin;
  int looked = 0, border = 0;
  for (const Eigen::Vector2d& d : directions<24, 0>()) {
    const Eigen::Vector2d pin = circle.c + rIn * d, pout = circle.c + rOut * d;
    if (!insideImage(img, pin.x(), pin.y(), 0.5) || !insideImage(img, pout.x(), pout.y(), 0.5)) continue;
    ++looked;
    const PixelColour out = sampleColour(img, pout.x(), pout.y());
    if (onField(out)) {
      ++border;
      continue;
    }
    const PixelColour in = sampleColour(img, pin.x(), pin.y());
    const double dy = out.y - in.y, du = out.u - in.u, dv = out.v - in.v;
    border += dy * dy + du * du + dv * dv >= step * step;
  }
  return looked ? static_cast<double>(border) / looked : 0;
}

// A goal post (or a robot's leg) seen above its foot: a narrow upright object carries on
// straight above the circle, about as wide as the ball (but wider than a line), and as bright
// as the candidate's white parts -- the candidate is then the foot of that surface. A ball in
// front of a wall or a board has wide background above it, or field; one in front of a
// person's dark shoe or trouser leg has something far darker than its white above it.
bool postAbove(const CameraImage& img, const FieldTest& onField, const CameraMatrix& cm, const Circle& circle,
               double radiusM, double white) {
  const Eigen::Vector2d up = imageUp(cm, circle.c, radiusM), side(-up.y(), up.x());
  const Eigen::Vector2d above = circle.c + 1.25 * circle.r * up;
  if (!insideImage(img, above.x(), above.y(), 0.5) || onField.at(img, above)) return false;
  int narrow = 0, looked = 0;
  for (double k : {1.5, 2.0, 2.6, 3.2}) {
    const Eigen::Vector2d q = circle.c + k * circle.r * up;
    if (!insideImage(img, q.x(), q.y(), 0.5)) continue;
    const PixelColour ref = sampleColour(img, q.x(), q.y());
    ++looked;
    if (onField(ref) || ref.y < 0.5 * white) continue;
    const double tol = 0.3 * ref.y + 10;
    auto extent = [&](double dir) {
      double t = 1;
      for (; t <= 3 * circle.r; t += std::max(1.0, 0.25 * circle.r)) {
        const Eigen::Vector2d p = q + dir * t * side;
        if (!insideImage(img, p.x(), p.y(), 0.5)) return 1e9;  // unknown: treat as wide
        const PixelColour col = sampleColour(img, p.x(), p.y());
        if (std::abs(col.y - ref.y) > tol || onField(col)) break;
      }
      return t;
    };
    // As wide as a post (the ball's diameter), not as a field line running up the image
    // from a ball lying on it (half that).
    const double left = extent(1), right = extent(-1);
    narrow += left < 1.6 * circle.r && right < 1.6 * circle.r && left + right >= 1.5 * circle.r;
  }
  return narrow >= 2 && 2 * narrow >= looked;
}

}  // namespace

BallPercept detectBall(const CameraImage& image, const ScanLineRegions& regions, const FieldReference& field,
                       const ObstaclesPercept& /*obstacles*/, const CameraMatrix& cm, const BallParams& params,
                       std::vector<BallCandidate>* debug) {
  BallPercept best;
  if (!field.valid) return best;
  const FieldTest onField(field);

  // 1. Candidates.
  std::vector<BallCandidate> cands;
  auto pixelOn = [](const ScanLine& sl, bool vertical, double along) {
    return vertical ? Eigen::Vector2d(sl.coord + 0.5, along) : Eigen::Vector2d(along, sl.coord + 0.5);
  };
  auto add = [&](const Eigen::Vector2d& seed, double r, bool vertical, int priority, bool fromPatch) {
    for (const auto& c : cands)
      if ((c.seed - seed).norm() < 0.7 * std::max(r, c.expectedRadius)) return;
    BallCandidate c;
    c.seed = seed;
    c.expectedRadius = r;
    c.priority = priority;
    c.alongVertical = vertical;
    c.fromPatch = fromPatch;
    cands.push_back(c);
  };
  // A cheap look across a run: the non-field stretch through the seed at right angles to
  // the scan line must be about as wide as a ball (not a line's edge, not a robot).
  auto acrossFits = [&](const Eigen::Vector2d& seed, double r, const Eigen::Vector2d& dir) {
    double width = 0;
    const double step = std::max(1.0, 0.25 * r);
    for (double sgn : {-1.0, 1.0}) {
      double t = 0;
      while (t < 2 * params.maxRadiusRatio * r + 2) {
        const Eigen::Vector2d p = seed + sgn * (t + step) * dir;
        if (!insideImage(image, p.x(), p.y(), 0.5)) break;  // cut by the border: keep what is seen
        if (onField.at(image, p)) break;
        t += step;
      }
      width += t;
    }
    return width >= 0.6 * r && width <= 2 * params.maxRadiusRatio * r + 3;
  };
  auto scan = [&](const std::vector<ScanLine>& lines, bool vertical) {
    const Eigen::Vector2d acrossDir = vertical ? Eigen::Vector2d(1, 0) : Eigen::Vector2d(0, 1);
    for (const ScanLine& sl : lines) {
      const auto& rs = sl.regions;
      for (std::size_t i = 0; i < rs.size();) {
        if (rs[i].cls == RegionClass::Field) {
          ++i;
          continue;
        }
        std::size_t j = i;
        bool bright = false, dark = false;
        double brightest = 0;
        while (j < rs.size() && rs[j].cls != RegionClass::Field) {
          const bool b = field.isWhiteRegion(rs[j]) || rs[j].colour.y > field.yMax;
          bright = bright || b;
          if (b) brightest = std::max<double>(brightest, rs[j].colour.y);
          dark = dark || rs[j].colour.y < 0.8 * field.fieldY;
          ++j;
        }
        const std::size_t first = i, last = j;  // the run is [first, last)
        i = j;
        if (!bright) continue;
        const int from = rs[first].from, to = rs[last - 1].to;
        // Black patches: dark regions with a bright one next to them on this line (no longer
        // than the ball: the patches and the shaded lower half may merge into one).
        for (std::size_t k = first; k < last; ++k) {
          if (rs[k].colour.y >= 0.5 * brightest) continue;
          const bool brightBefore = k > first && rs[k - 1].colour.y >= 0.75 * brightest;
          const bool brightAfter = k + 1 < last && rs[k + 1].colour.y >= 0.75 * brightest;
          if (!brightBefore && !brightAfter) continue;
          const Eigen::Vector2d seed = pixelOn(sl, vertical, 0.5 * (rs[k].from + rs[k].to));
          const double r = expectedBallRadius(cm, seed, params.radius);
          if (r >= 1.5 && rs[k].to - rs[k].from <= 2 * r) add(seed, r, vertical, 0, true);
        }
        // The run as a whole: as long as a ball, a candidate at its middle; longer (a ball
        // touching a line or another white thing), one at each end; much longer, none.
        const double len = to - from;
        const double rMid = expectedBallRadius(cm, pixelOn(sl, vertical, 0.5 * (from + to)), params.radius);
        if (rMid < 1.5 || len < std::max(2.0, 0.4 * rMid)) continue;
        auto addChecked = [&](double along) {
          const Eigen::Vector2d seed = pixelOn(sl, vertical, along);
          const double r = expectedBallRadius(cm, seed, params.radius);
          // A run with a dark part (a black patch) may lie on a line that runs on across it.
          if (r >= 1.5 && (dark || acrossFits(seed, r, acrossDir))) add(seed, r, vertical, dark ? 0 : 1, false);
        };
        if (len <= 2 * params.maxRadiusRatio * rMid + 2) {
          addChecked(0.5 * (from + to));
        } else if (len <= 6 * rMid) {
          addChecked(from + rMid);
          addChecked(to - rMid);
        }
      }
    }
  };
  scan(regions.vertical, true);
  scan(regions.horizontal, false);
  // Those with a black patch or a dark part first; at most maxCandidates are verified.
  std::stable_sort(cands.begin(), cands.end(),
                   [](const BallCandidate& a, const BallCandidate& b) { return a.priority < b.priority; });
  if (static_cast<int>(cands.size()) > params.maxCandidates) cands.resize(params.maxCandidates);

  // 2. Verification.
  std::vector<Circle> measured;  // circles already measured (several seeds find the same ball)
  bool bestByClassifier = false;
  for (BallCandidate& c : cands) {
    bool duplicate = false;
    for (const Circle& m : measured) duplicate = duplicate || (c.seed - m.c).norm() < 0.5 * m.r;
    if (duplicate) {
      c.rejectedBy = "duplicate";
      continue;
    }
    Circle circle;
    if (!fitOutline(image, onField, params, c, circle, debug != nullptr)) {
      c.rejectedBy = "outline";
      continue;
    }
    c.fitted = true;
    c.centre = circle.c;
    c.radius = circle.r;
    const double expected = expectedBallRadius(cm, circle.c, params.radius);
    if (expected <= 0 || circle.r < params.minRadiusRatio * expected || circle.r > params.maxRadiusRatio * expected) {
      c.rejectedBy = "size";
      continue;
    }
    if (params.ownBody && params.ownBody->hides(cm, circle.c)) {
      c.rejectedBy = "own body";
      continue;
    }
    measured.push_back(circle);
    // 16 samples a ring; where the image border cuts the ball, denser rings over what is left.
    Inside in = measureInside<16>(image, field, onField, circle);
    const double visible = in.n / (4.0 * 16 + 1);  // about the fraction of the disc in the image
    if (in.n < 48) in = measureInside<48>(image, field, onField, circle);
    if (in.n < 16) {
      c.rejectedBy = "inside off image";
      continue;
    }
    const Around ar = measureAround(image, field, onField, circle);
    c.contrast = in.contrast, c.darkRatio = in.darkRatio, c.fieldInside = in.fieldRatio, c.bright = in.white;
    c.pattern = in.pattern, c.satInside = in.relSat;
    c.fieldAround = ar.n ? static_cast<double>(ar.field) / ar.n : 0;
    c.satAround = ar.relSat;
    c.surround = ar.y;
    // Hard figures: a ball has black patches (contrast, a dark share) and lies on the field.
    if (in.contrast < params.minContrast) {
      c.rejectedBy = "contrast";
      continue;
    }
    if (in.darkRatio < params.minDarkInside || in.darkRatio > params.maxDarkInside) {
      c.rejectedBy = "pattern";
      continue;
    }
    if (ar.field == 0) {
      c.rejectedBy = "not on field";
      continue;
    }
    c.support = outlineSupport(image, onField, circle, in.white);
    // Soft figures, the first that falls short.
    static constexpr const char* kFieldInside = "field inside";
    const char* soft = nullptr;
    // Grey: far less saturated (from this image's white point) than the field beside it. Not
    // "brighter than the field": a ball seen from its shaded side is darker than sunlit grass.
    if (in.fieldRatio > params.maxFieldInside) {
      soft = kFieldInside;
    } else if (in.relSat > params.maxGreyness * ar.relSat) {
      soft = "colour";
    } else {
      // A ball cut by the image border to less than the eval's three quarters shows only part
      // of its pattern and outline: all of what is seen must be right.
      const bool cut = visible < params.minVisible;
      const bool outlineAll = c.inliers >= params.cutMinOutline * (kRays - c.offImage);
      const bool patches = in.pattern >= params.minPattern;
      const bool clear = patches && (cut ? in.contrast >= params.cutMinContrast && outlineAll &&
                                               c.support >= params.cutMinSupport && c.fieldAround >= params.cutMinSupport
                                         : in.contrast >= params.clearContrast &&
                                               in.contrast + 0.5 * (c.support + c.fieldAround) >= params.clearEvidence);
      const bool faint = visible >= 1 && c.offImage == 0 && in.pattern >= params.faintMinPattern &&
                         in.darkRatio >= params.faintMinDark && in.darkRatio <= params.faintMaxDark &&
                         c.support >= params.faintMinSupport && c.fieldAround >= params.faintMinAround &&
                         circle.r >= params.faintMinRadiusPx;
      if (!clear && !faint) soft = "evidence";
    }
    if (soft) {
      // The second opinion: only where the ball has taken the field's colour (lit from behind,
      // by the light off the carpet), so that the colour the classical figures read is not its
      // own; only on a whole circle in the image, big enough to show its patches.
      // Where the outline is weak, the fit is off by up to half a radius: a circle that the
      // network already half believes is looked at again a quarter radius and a tenth of the
      // size around it, and the best of those counts.
      if (params.classifier && soft == kFieldInside && in.fieldRatio <= params.learnedMaxFieldInside && visible >= 1 &&
          c.offImage == 0 && circle.r >= params.learnedMinRadiusPx) {
        c.learned = params.classifier->score(image, circle.c, circle.r);
        if (c.learned >= params.learnedSearchScore && c.learned < params.minLearnedScore) {
          Circle refined = circle;
          for (double k : {0.9, 1.0, 1.1})
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx) {
                const Circle t{circle.c + 0.25 * circle.r * Eigen::Vector2d(dx, dy), k * circle.r};
                if (!insideImage(image, t.c.x() - t.r, t.c.y() - t.r) || !insideImage(image, t.c.x() + t.r, t.c.y() + t.r))
                  continue;
                const double sc = params.classifier->score(image, t.c, t.r);
                if (sc > c.learned) c.learned = sc, refined = t;
              }
          circle = refined;
        }
      }
      if (c.learned < params.minLearnedScore) {
        c.rejectedBy = soft;
        continue;
      }
      c.byClassifier = true;
      c.centre = circle.c;
      c.radius = circle.r;
    }
    if (postAbove(image, onField, cm, circle, params.radius, in.white)) {
      c.rejectedBy = "post";
      continue;
    }
    c.accepted = true;
    c.score = in.contrast + c.support + c.fieldAround;
    // A ball the classical figures accept beats one only the classifier accepts (its circle is
    // the outline fit's, only searched about where the network half believed it).
    if (!best.seen || (bestByClassifier && !c.byClassifier) ||
        (bestByClassifier == c.byClassifier && c.score > best.confidence)) {
      const auto pos = cm.pixelToGround(circle.c, params.radius);
      if (!pos) continue;
      best.seen = true;
      bestByClassifier = c.byClassifier;
      best.image = circle.c;
      best.radiusPx = circle.r;
      best.position = *pos;
      best.confidence = c.score;
      best.covariance = ballCovariance(cm, circle.c, circle.r, params.radius);
    }
  }
  if (best.seen) best.confidence = std::min(1.0, best.confidence / 3);
  if (debug) *debug = std::move(cands);
  return best;
}

}  // namespace nao::vision
