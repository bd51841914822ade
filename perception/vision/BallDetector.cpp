#include "perception/vision/BallDetector.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "perception/vision/ColourTests.h"

namespace nao::vision {

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

struct Circle {
  Eigen::Vector2d c;
  double r;
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
  std::vector<double> angles;
  int offImage = 0;  // rays that left the image before reaching the field
};

// From `centre`, walks `rays` rays up to maxLen and records where the field starts (two field
// samples in a row). Rays that leave the image or never reach the field are dropped.
Outline castRays(const CameraImage& img, const FieldReference& field, const Eigen::Vector2d& centre, double maxLen,
                 int rays) {
  Outline o;
  // Coarse steps (about a sixth of the expected radius), then bisection to the pixel.
  const double step = std::max(1.0, maxLen / 15);
  auto isField = [&](const Eigen::Vector2d& p) { return field.isField(sampleColour(img, p.x(), p.y())); };
  for (int k = 0; k < rays; ++k) {
    const double a = 2 * M_PI * k / rays;
    const Eigen::Vector2d d(std::cos(a), std::sin(a));
    double lastOff = 0;  // the last step not on the field
    for (double t = step; t <= maxLen; t += step) {
      const Eigen::Vector2d p = centre + t * d;
      if (!insideImage(img, p.x(), p.y(), 0.5)) {
        ++o.offImage;
        break;
      }
      if (!isField(p)) {
        lastOff = t;
        continue;
      }
      // Field here: is it more than a speck (the next sample too, or half a step on)?
      const Eigen::Vector2d q = centre + (t + std::max(1.0, 0.5 * step)) * d;
      if (insideImage(img, q.x(), q.y(), 0.5) && !isField(q)) continue;
      double lo = lastOff, hi = t;
      while (hi - lo > 0.75) {
        const double mid = 0.5 * (lo + hi);
        (isField(centre + mid * d) ? hi : lo) = mid;
      }
      o.edges.push_back(centre + 0.5 * (lo + hi) * d);
      o.angles.push_back(a);
      break;
    }
  }
  return o;
}

// The outline where the field is not beside the ball (a foot, a line, a shadow): along each
// ray the outermost pixel as bright as the ball's white parts, provided darker pixels follow
// (a ray running on into other white paint is dropped).
Outline castBrightRays(const CameraImage& img, const Eigen::Vector2d& centre, double expectedR, int rays) {
  Outline o;
  // The ball's white level: bright samples near the centre.
  std::array<double, 48> ys{};
  int n = 0;
  for (double rr : {0.3, 0.6})
    for (int k = 0; k < 24 && n < 48; ++k) {
      const Eigen::Vector2d p = centre + rr * expectedR * Eigen::Vector2d(std::cos(k * M_PI / 12), std::sin(k * M_PI / 12));
      if (insideImage(img, p.x(), p.y(), 0.5)) ys[n++] = sampleColour(img, p.x(), p.y()).y;
    }
  if (n < 12) return o;
  std::sort(ys.begin(), ys.begin() + n);
  const double level = 0.75 * ys[n * 8 / 10];
  const double step = std::max(0.75, expectedR / 12);
  for (int k = 0; k < rays; ++k) {
    const double a = 2 * M_PI * k / rays;
    const Eigen::Vector2d d(std::cos(a), std::sin(a));
    double lastBright = -1;
    int darkAfter = 0;
    bool left = false;
    for (double t = 0.4 * expectedR; t <= 1.9 * expectedR; t += step) {
      const Eigen::Vector2d p = centre + t * d;
      if (!insideImage(img, p.x(), p.y(), 0.5)) {
        left = true;
        break;
      }
      if (sampleColour(img, p.x(), p.y()).y >= level) {
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
    o.edges.push_back(centre + (lastBright + 0.5 * step) * d);
    o.angles.push_back(a);
  }
  return o;
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

// A circle through the outline that most outline points agree with (a ball touching a line
// or lying in its shadow has outline points on those instead): circles through spread
// triples of points, the one with most points near it (ties: the radius nearest the
// expected one), refitted to those. The angular span of the agreeing points must be wide
// enough to pin the circle down.
bool robustFit(const Outline& o, Circle& c, int& inliers, double expectedR) {
  const int n = static_cast<int>(o.edges.size());
  if (n < 5) return false;
  auto agreeing = [&](const Circle& h) {
    int count = 0;
    const double tol = std::max(1.5, 0.12 * h.r);
    for (const auto& p : o.edges) count += std::abs((p - h.c).norm() - h.r) < tol;
    return count;
  };
  Circle best{};
  int bestCount = 0;
  double bestDev = 1e9;
  auto consider = [&](const Circle& h) {
    if (!(h.r > 0.5 * expectedR && h.r < 2 * expectedR)) return;
    const int count = agreeing(h);
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
  std::vector<double> angles;
  const double tol = std::max(1.5, 0.12 * best.r);
  for (const auto& p : o.edges)
    if (std::abs((p - best.c).norm() - best.r) < tol) {
      keep.push_back(p);
      angles.push_back(std::atan2(p.y() - best.c.y(), p.x() - best.c.x()));
    }
  c = best;
  if (keep.size() < 5 || !fitCircle(keep, c)) return false;
  inliers = static_cast<int>(keep.size());
  // The largest empty angular gap must be < 220 deg (at least ~140 deg of outline seen).
  std::sort(angles.begin(), angles.end());
  double gap = angles.front() + 2 * M_PI - angles.back();
  for (std::size_t i = 1; i < angles.size(); ++i) gap = std::max(gap, angles[i] - angles[i - 1]);
  return gap < 220 * M_PI / 180;
}

}  // namespace

BallPercept detectBall(const CameraImage& image, const ScanLineRegions& regions, const FieldReference& field,
                       const ObstaclesPercept& /*obstacles*/, const CameraMatrix& cm, const BallParams& params,
                       std::vector<BallCandidate>* debug) {
  BallPercept best;
  if (!field.valid) return best;

  // 1. Candidates: runs of non-field regions as long as a ball there.
  std::vector<BallCandidate> cands;
  auto consider = [&](const std::vector<ScanLine>& lines, bool vertical) {
    for (const ScanLine& sl : lines) {
      const auto& rs = sl.regions;
      for (std::size_t i = 0; i < rs.size();) {
        if (rs[i].cls == RegionClass::Field) {
          ++i;
          continue;
        }
        std::size_t j = i;
        bool bright = false, dark = false;
        while (j < rs.size() && rs[j].cls != RegionClass::Field) {
          bright = bright || field.isWhiteRegion(rs[j]) || rs[j].colour.y > field.yMax;
          dark = dark || rs[j].colour.y < 0.8 * field.fieldY;
          ++j;
        }
        const int from = rs[i].from, to = rs[j - 1].to;
        i = j;
        if (!bright) continue;
        // A run as long as a ball gives a candidate at its middle; a longer one (a ball
        // touching a line or another white thing) one at each end; a much longer one none.
        auto add = [&](double along) {
          const Eigen::Vector2d seed =
              vertical ? Eigen::Vector2d(sl.coord + 0.5, along) : Eigen::Vector2d(along, sl.coord + 0.5);
          const double r = expectedBallRadius(cm, seed, params.radius);
          if (r < 1.5) return;
          for (const auto& c : cands)
            if ((c.seed - seed).norm() < 0.7 * std::max(r, c.expectedRadius)) return;
          BallCandidate c;
          c.seed = seed;
          c.expectedRadius = r;
          c.priority = dark ? 0 : 1;
          c.alongVertical = vertical;
          cands.push_back(c);
        };
        const double len = to - from;
        const double rMid = expectedBallRadius(cm, vertical ? Eigen::Vector2d(sl.coord + 0.5, 0.5 * (from + to))
                                                            : Eigen::Vector2d(0.5 * (from + to), sl.coord + 0.5),
                                               params.radius);
        if (rMid < 1.5 || len < std::max(2.0, 0.4 * rMid)) continue;
        if (len <= 2 * params.maxRadiusRatio * rMid + 2) {
          add(0.5 * (from + to));
        } else if (len <= 6 * rMid) {
          add(from + rMid);
          add(to - rMid);
        }
      }
    }
  };
  consider(regions.vertical, true);
  consider(regions.horizontal, false);
  // A cheap look across the run: the non-field stretch through the seed at right angles to
  // the scan line must be about as wide as a ball (not a line's edge, not a robot).
  auto across = [&](const BallCandidate& c, const Eigen::Vector2d& dir) {
    double width = 0;
    for (double sgn : {-1.0, 1.0}) {
      double t = 0;
      const double step = std::max(1.0, 0.25 * c.expectedRadius);
      while (t < 2 * params.maxRadiusRatio * c.expectedRadius + 2) {
        const Eigen::Vector2d p = c.seed + sgn * (t + step) * dir;
        if (!insideImage(image, p.x(), p.y(), 0.5)) break;  // cut by the border: keep what is seen
        if (field.isField(sampleColour(image, p.x(), p.y()))) break;
        t += step;
      }
      width += t;
    }
    return width;
  };
  std::vector<BallCandidate> kept;
  for (BallCandidate& c : cands) {
    const double w = across(c, c.alongVertical ? Eigen::Vector2d(1, 0) : Eigen::Vector2d(0, 1));
    if (w < 0.6 * c.expectedRadius || w > 2 * params.maxRadiusRatio * c.expectedRadius + 3) continue;
    kept.push_back(c);
  }
  cands = std::move(kept);
  // Runs with a dark part (the black patches) first; at most maxCandidates are verified.
  std::stable_sort(cands.begin(), cands.end(),
                   [](const BallCandidate& a, const BallCandidate& b) { return a.priority < b.priority; });
  if (static_cast<int>(cands.size()) > params.maxCandidates) cands.resize(params.maxCandidates);

  // 2. Verification.
  for (BallCandidate& c : cands) {
    Circle circle{c.seed, c.expectedRadius};
    int inliers = 0, offImage = 0;
    bool ok = false;
    for (int pass = 0; pass < 2; ++pass) {
      const Outline o = castRays(image, field, circle.c, 2.4 * std::max(circle.r, c.expectedRadius), params.rays);
      ok = robustFit(o, circle, inliers, c.expectedRadius);
      offImage = o.offImage;
      if (!ok) break;
    }
    // Most rays that stay in the image must meet the field on the circle: round, and on the field.
    bool fieldOutline = ok && inliers >= params.minOutline * (params.rays - offImage);
    if (!fieldOutline) {
      // Second chance where something else touches the ball: the outline of its bright parts.
      circle = Circle{c.seed, c.expectedRadius};
      ok = false;
      for (int pass = 0; pass < 2; ++pass) {
        const Outline o = castBrightRays(image, circle.c, c.expectedRadius, params.rays);
        ok = robustFit(o, circle, inliers, c.expectedRadius);
        offImage = o.offImage;
        if (!ok) break;
      }
      if (!ok || inliers < params.minOutline * (params.rays - offImage)) {
        c.rejectedBy = "outline";
        c.inliers = inliers;
        continue;
      }
    }
    c.byBrightOutline = !fieldOutline;
    c.fitted = true;
    c.inliers = inliers;
    c.centre = circle.c;
    c.radius = circle.r;
    const double expected = expectedBallRadius(cm, circle.c, params.radius);
    if (expected <= 0 || circle.r < params.minRadiusRatio * expected || circle.r > params.maxRadiusRatio * expected) {
      c.rejectedBy = "size";
      continue;
    }
    // Inside: a polar grid of samples within 0.8 r.
    std::array<double, 64> ys{};
    int n = 0, fieldInside = 0;
    double satInside = 0;
    for (double rr : {0.2, 0.45, 0.65, 0.8})
      for (int k = 0; k < 16; ++k) {
        const double a = 2 * M_PI * (k + 0.5 * (rr > 0.5)) / 16;
        const Eigen::Vector2d p = circle.c + rr * circle.r * Eigen::Vector2d(std::cos(a), std::sin(a));
        if (!insideImage(image, p.x(), p.y(), 0.5)) continue;
        const PixelColour col = sampleColour(image, p.x(), p.y());
        ys[n++] = col.y;
        fieldInside += field.isField(col);
        satInside += field.relSat(col);
      }
    if (n < 16) {
      c.rejectedBy = "inside off image";
      continue;
    }
    std::sort(ys.begin(), ys.begin() + n);
    const double bright = ys[n * 9 / 10], darkLevel = ys[n / 10];
    const double contrast = (bright - darkLevel) / std::max(1.0, bright);
    const double split = darkLevel + 0.35 * (bright - darkLevel);
    int dark = 0;
    for (int i = 0; i < n; ++i) dark += ys[i] < split;
    // Around: a ring at 1.4 r.
    int around = 0, fieldAround = 0;
    double yAround = 0, satAround = 0;
    for (int k = 0; k < 16; ++k) {
      const double a = 2 * M_PI * k / 16;
      const Eigen::Vector2d p = circle.c + 1.4 * circle.r * Eigen::Vector2d(std::cos(a), std::sin(a));
      if (!insideImage(image, p.x(), p.y(), 0.5)) continue;
      const PixelColour col = sampleColour(image, p.x(), p.y());
      ++around;
      if (field.isField(col)) ++fieldAround, yAround += col.y, satAround += field.relSat(col);
    }
    const double fieldInsideRatio = static_cast<double>(fieldInside) / n;
    const double darkRatio = static_cast<double>(dark) / n;
    c.contrast = contrast, c.darkRatio = darkRatio, c.fieldInside = fieldInsideRatio, c.bright = bright;
    c.fieldAround = around ? static_cast<double>(fieldAround) / around : 0;
    c.satInside = satInside / n;
    if (fieldAround) c.yAround = yAround / fieldAround, c.satAround = satAround / fieldAround;
    if (fieldInsideRatio > params.maxFieldInside) {
      c.rejectedBy = "field inside";
      continue;
    }
    if (contrast < params.minContrast) {
      c.rejectedBy = "contrast";
      continue;
    }
    if (darkRatio < params.minDarkInside || darkRatio > params.maxDarkInside) {
      c.rejectedBy = "pattern";
      continue;
    }
    if (around == 0 || fieldAround < params.minFieldAround * around) {
      c.rejectedBy = "not on field";
      continue;
    }
    yAround /= fieldAround;
    satAround /= fieldAround;
    // Grey: far less saturated (from this image's white point) than the field beside it. Not
    // "brighter than the field": a ball seen from its shaded side is darker than sunlit grass.
    if (satInside / n > params.maxGreyness * satAround) {
      c.rejectedBy = "colour";
      continue;
    }
    // A goal post (or a robot's leg): a narrow upright object continues above the circle,
    // about as wide as the ball. A ball in front of a wall or a board has wide background
    // above it, or field.
    const Eigen::Vector2d up = imageUp(cm, circle.c, params.radius), side(-up.y(), up.x());
    int narrow = 0, looked = 0;
    for (double k : {1.5, 2.0, 2.6, 3.2}) {
      const Eigen::Vector2d q = circle.c + k * circle.r * up;
      if (!insideImage(image, q.x(), q.y(), 0.5)) continue;
      const PixelColour ref = sampleColour(image, q.x(), q.y());
      ++looked;
      if (field.isField(ref)) continue;
      const double tol = 0.3 * ref.y + 10;
      auto extent = [&](double dir) {
        double t = 1;
        for (; t <= 3 * circle.r; t += std::max(1.0, 0.25 * circle.r)) {
          const Eigen::Vector2d p = q + dir * t * side;
          if (!insideImage(image, p.x(), p.y(), 0.5)) return 1e9;  // unknown: treat as wide
          const PixelColour col = sampleColour(image, p.x(), p.y());
          if (std::abs(col.y - ref.y) > tol || field.isField(col)) break;
        }
        return t;
      };
      narrow += extent(1) < 1.6 * circle.r && extent(-1) < 1.6 * circle.r;
    }
    if (narrow >= 2 && 2 * narrow >= looked) {
      c.rejectedBy = "post";
      continue;
    }
    c.accepted = true;
    c.score = inliers / static_cast<double>(params.rays) + contrast + static_cast<double>(fieldAround) / around;
    if (!best.seen || c.score > best.confidence) {
      const auto pos = cm.pixelToGround(circle.c, params.radius);
      if (!pos) continue;
      best.seen = true;
      best.image = circle.c;
      best.radiusPx = circle.r;
      best.position = *pos;
      best.confidence = c.score;
      // Covariance: the centre pixel's uncertainty through the ray-plane intersection.
      const double sigmaPx = std::max(0.5, 0.08 * circle.r);
      Eigen::Matrix2d j;
      for (int axis = 0; axis < 2; ++axis) {
        Eigen::Vector2d d = Eigen::Vector2d::Zero();
        d[axis] = 0.5;
        const auto a = cm.pixelToGround(circle.c + d, params.radius), b = cm.pixelToGround(circle.c - d, params.radius);
        j.col(axis) = a && b ? Eigen::Vector2d(*a - *b) : Eigen::Vector2d(0.1, 0.1);
      }
      best.covariance = sigmaPx * sigmaPx * j * j.transpose() + 1e-6 * Eigen::Matrix2d::Identity();
    }
  }
  if (best.seen) best.confidence = std::min(1.0, best.confidence / 3);
  if (std::getenv("NAO_BALLSTAT") && best.seen)  // TEMP
    for (const auto& c : cands)
      if (c.accepted && c.centre == best.image)
        std::fprintf(stderr, "BALLCAND r %.1f re %.1f con %.2f dark %.2f fin %.2f far %.2f bright %.0f yA %.0f sI %.1f sA %.1f inl %d\n",
                     c.radius, c.expectedRadius, c.contrast, c.darkRatio, c.fieldInside, c.fieldAround, c.bright, c.yAround,
                     c.satInside, c.satAround, c.inliers + 100 * c.byBrightOutline);
  if (debug) *debug = std::move(cands);
  return best;
}

}  // namespace nao::vision
