#include "perception/vision/FieldBoundaryDetector.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace nao {
namespace {

struct Point {
  double x, y;
  bool open;  // the field reaches the top of the scanned line: the boundary is here or above
};

struct Line {
  double m = 0, c = 0;  // y = m x + c
  double at(double x) const { return m * x + c; }
};

// y = max(l1, l2) (one line when !corner).
struct Model {
  Line l1, l2;
  bool corner = false;
  double at(double x) const { return corner ? std::max(l1.at(x), l2.at(x)) : l1.at(x); }
};

constexpr double kMaxSlope = 3.0;
constexpr double kAbovePenalty = 1.0;
constexpr double kMinSupport = 0.15;   // of the points a fit must explain (net of the points above it)  // a point above the boundary costs as much as an inlier gains

double score(const Model& model, const std::vector<Point>& pts, double tol) {
  double s = 0;
  for (const Point& p : pts) {
    const double r = p.y - model.at(p.x);  // > 0: the point lies below the boundary
    if (std::abs(r) <= tol || (p.open && r >= -tol)) s += 1;
    else if (r < -tol) s -= kAbovePenalty;
  }
  return s;
}

bool through(const Point& a, const Point& b, Line& l) {
  if (std::abs(b.x - a.x) < 1) return false;
  l.m = (b.y - a.y) / (b.x - a.x);
  l.c = a.y - l.m * a.x;
  return std::abs(l.m) <= kMaxSlope;
}

// Least squares over the points within tol of the line (keeping the line if too few).
Line refine(const Line& l, const std::vector<Point>& pts, double tol, double fromX, double toX) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (const Point& p : pts) {
    if (p.x < fromX || p.x > toX || p.open) continue;
    if (std::abs(p.y - l.at(p.x)) > tol) continue;
    sx += p.x, sy += p.y, sxx += p.x * p.x, sxy += p.x * p.y, ++n;
  }
  if (n < 3) return l;
  const double det = n * sxx - sx * sx;
  if (std::abs(det) < 1e-9) return l;
  Line r;
  r.m = (n * sxy - sx * sy) / det;
  r.c = (sy - r.m * sx) / n;
  return std::abs(r.m) <= kMaxSlope ? r : l;
}

// Small deterministic generator: the same image gives the same boundary.
struct Rng {
  std::uint64_t s = 0x9E3779B97F4A7C15ull;
  int below(int n) {
    s ^= s << 13, s ^= s >> 7, s ^= s << 17;
    return static_cast<int>(s % static_cast<std::uint64_t>(n));
  }
};

}  // namespace

FieldBoundary detectFieldBoundary(const CameraImage& image, const ScanLineRegions& regions, const CameraMatrix&) {
  FieldBoundary boundary;
  if (!regions.fieldColour.valid || image.width <= 0) return boundary;
  const double W = image.width, H = image.height;

  // The candidate point of each vertical line: where the running score from the bottom
  // (+ field, - other; white neutral: lines lie on the field; saturated (unknown) neutral:
  // no colour to go by) peaks.
  std::vector<Point> pts;
  for (const ScanLine& line : regions.vertical) {
    double s = 0, best = 0;
    int bestY = -1;
    for (auto it = line.regions.rbegin(); it != line.regions.rend(); ++it) {
      const int len = it->to - it->from;
      if (it->cls == RegionClass::Field) s += len;
      else if (it->cls == RegionClass::Other) s -= len;
      if (s > best) best = s, bestY = it->from;
    }
    if (bestY < 0 || best < 2) continue;
    pts.push_back({line.coord + 0.5, static_cast<double>(bestY), bestY <= line.start});
  }
  if (pts.size() < 3) return boundary;
  const double tol = std::max(2.0, H / 100.0);
  const int n = static_cast<int>(pts.size());

  // RANSAC: one line, then a corner (two lines through a common point).
  Rng rng;
  Model best;
  double bestScore = -1e9;
  for (int it = 0; it < 120; ++it) {
    Model m;
    if (!through(pts[rng.below(n)], pts[rng.below(n)], m.l1)) continue;
    const double s = score(m, pts, tol);
    if (s > bestScore) bestScore = s, best = m;
  }
  if (bestScore < -1e8) {  // all points in one column: a level line through their median
    std::vector<double> ys;
    for (const Point& p : pts) ys.push_back(p.y);
    std::nth_element(ys.begin(), ys.begin() + ys.size() / 2, ys.end());
    best = Model{};
    best.l1.c = ys[ys.size() / 2];
    bestScore = score(best, pts, tol);
  }
  best.l1 = refine(best.l1, pts, tol, -1e9, 1e9);
  bestScore = score(best, pts, tol);
  Model bestCorner;
  double cornerScore = -1e9;
  for (int it = 0; it < 300; ++it) {
    int a = rng.below(n), c = rng.below(n), d = rng.below(n);
    if (pts[a].x > pts[d].x) std::swap(a, d);
    if (!(pts[a].x < pts[c].x && pts[c].x < pts[d].x)) continue;
    Model m;
    m.corner = true;
    if (!through(pts[a], pts[c], m.l1) || !through(pts[c], pts[d], m.l2) || m.l1.m >= m.l2.m) continue;
    const double s = score(m, pts, tol);
    if (s > cornerScore) cornerScore = s, bestCorner = m;
  }
  if (cornerScore > -1e8) {
    // Refine each side on its own points, then keep the corner only if it clearly helps.
    const double cx = (bestCorner.l2.c - bestCorner.l1.c) / (bestCorner.l1.m - bestCorner.l2.m);
    bestCorner.l1 = refine(bestCorner.l1, pts, tol, -1e9, cx);
    bestCorner.l2 = refine(bestCorner.l2, pts, tol, cx, 1e9);
    if (bestCorner.l1.m < bestCorner.l2.m) {
      cornerScore = score(bestCorner, pts, tol);
      if (cornerScore >= bestScore + std::max(3.0, 0.05 * n)) best = bestCorner, bestScore = cornerScore;
    }
  }
  if (bestScore < std::max(3.0, kMinSupport * n)) {
    // No line explains the points (a field broken up by sun and shadow, or mostly hidden):
    // a level boundary through the upper points, so that little field is cut away.
    std::vector<double> ys;
    for (const Point& p : pts) ys.push_back(p.y);
    std::nth_element(ys.begin(), ys.begin() + ys.size() / 10, ys.end());
    best = Model{};
    best.l1.c = ys[ys.size() / 10];
  }

  boundary.valid = true;
  boundary.points.emplace_back(0.0, best.at(0));
  if (best.corner) {
    const double cx = (best.l2.c - best.l1.c) / (best.l1.m - best.l2.m);
    if (cx > 0 && cx < W) boundary.points.emplace_back(cx, best.at(cx));
  }
  boundary.points.emplace_back(W, best.at(W));
  return boundary;
}

}  // namespace nao
