#include "perception/vision/ObstacleDetector.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace nao {
namespace {

// Geometry of a NAO (m), not tuned for any light.
constexpr double kLowerBodyHeight = 0.25;  // a run at least this tall (image) at its foot point
constexpr double kRobotHeight = 0.58;
constexpr double kMinWidth = 0.08;         // joined runs at least this wide at the foot point
constexpr double kMaxWidth = 1.5;          // m: wider is no group of robots
constexpr double kFieldGapPx = 3;          // field this short inside a run does not end it (but at the boundary)
constexpr double kBelowBoundaryPx = 3;     // a run must end this far below the boundary

struct Run {
  double x;
  int top, bottom;
  double legPx;  // image width of a robot's leg at the run's foot
  bool fromTop;  // reaches up to the field boundary (or the scan line's start): its top is not seen
};

// Image size of a vertical stretch of `height` standing at the ground point of pixel (x, y),
// and the image width of `width` there.
bool sizesAt(const CameraMatrix& cm, double x, double y, double height, double width, double& hPx, double& wPx) {
  const auto g = cm.pixelToGround({x, y});
  if (!g) return false;
  const auto foot = cm.project({g->x(), g->y(), 0});
  const auto top = cm.project({g->x(), g->y(), height});
  Eigen::Vector2d lateral(-g->y(), g->x());
  if (lateral.norm() < 1e-6) return false;
  lateral = lateral.normalized() * width;
  const auto side = cm.project({g->x() + lateral.x(), g->y() + lateral.y(), 0});
  if (!foot || !top || !side) return false;
  hPx = (*foot - *top).norm();
  wPx = (*foot - *side).norm();
  return true;
}

}  // namespace

ObstaclesPercept detectObstacles(const CameraImage& image, const ScanLineRegions& regions, const FieldBoundary& boundary,
                                 const CameraMatrix& cmIn) {
  ObstaclesPercept out;
  if (!regions.fieldColour.valid || image.width <= 0) return out;
  CameraMatrix cm = cmIn;
  if (cm.intrinsics.width != image.width || cm.intrinsics.height != image.height) {
    const double sx = static_cast<double>(image.width) / cm.intrinsics.width;
    const double sy = static_cast<double>(image.height) / cm.intrinsics.height;
    cm.intrinsics.fx *= sx, cm.intrinsics.cx *= sx, cm.intrinsics.fy *= sy, cm.intrinsics.cy *= sy;
    cm.intrinsics.width = image.width, cm.intrinsics.height = image.height;
  }

  // Candidate runs: non-field stretches (field gaps of a few pixels bridged) that end below
  // the boundary. With the regions of the whole image, a robot standing near the boundary
  // rises above it in one run; what ends at the boundary is the world beyond the field.
  std::vector<Run> runs;
  for (const ScanLine& line : regions.vertical) {
    const auto& rs = line.regions;
    const double x = line.coord + 0.5;
    const double boundaryY = boundary.valid ? boundary.yAt(x) : -1e9;
    std::size_t k = 0;
    while (k < rs.size()) {
      if (rs[k].cls == RegionClass::Field) {
        ++k;
        continue;
      }
      const int top = rs[k].from;
      int bottom = rs[k].to;
      std::size_t j = k + 1;
      while (j < rs.size()) {
        if (rs[j].cls != RegionClass::Field) bottom = rs[j].to;
        else if (rs[j].to - rs[j].from > kFieldGapPx || rs[j].from <= boundaryY + kBelowBoundaryPx) break;
        ++j;
      }
      k = j;
      if (bottom < boundaryY + kBelowBoundaryPx) continue;
      double hPx, wPx;
      if (!sizesAt(cm, x, bottom - 0.5, kLowerBodyHeight, 0.05, hPx, wPx)) continue;
      const int len = bottom - top;
      const bool fromTop = top <= std::max<double>(line.start, boundaryY) + std::max(kBelowBoundaryPx, 0.25 * hPx);
      // Robot-tall, or reaching up to the boundary (or the image top) and much taller than a
      // field line is wide there (its image height is smaller still).
      if (len >= hPx || (fromTop && len >= 3.0 * wPx)) runs.push_back({x, top, bottom, 2 * wPx, fromTop});
    }
  }
  if (runs.empty()) return out;

  // Join runs on nearby lines that overlap in y.
  std::vector<int> parent(runs.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  // Runs come in x order (vertical lines ascend); join each with the following runs that
  // lie within a leg's width and overlap it in y.
  for (std::size_t a = 0; a < runs.size(); ++a) {
    const Run& ra = runs[a];
    const double reach = std::max(ra.legPx, 2.5 * image.width / 160.0);
    for (std::size_t b = a + 1; b < runs.size() && runs[b].x - ra.x <= reach; ++b) {
      const Run& rb = runs[b];
      if (rb.top >= ra.bottom || ra.top >= rb.bottom) continue;
      parent[find(static_cast<int>(b))] = find(static_cast<int>(a));
    }
  }
  std::vector<int> index(runs.size(), -1);
  std::vector<ObstaclesPercept::Obstacle> boxes;
  std::vector<double> minX, maxX;
  std::vector<char> topUnseen;
  for (std::size_t a = 0; a < runs.size(); ++a) {
    const int root = find(static_cast<int>(a));
    if (index[root] < 0) {
      index[root] = static_cast<int>(boxes.size());
      boxes.push_back({image.width, 0, image.height, 0, Eigen::Vector2d::Zero()});
      minX.push_back(1e9);
      maxX.push_back(-1e9);
      topUnseen.push_back(0);
    }
    const int i = index[root];
    minX[i] = std::min(minX[i], runs[a].x);
    maxX[i] = std::max(maxX[i], runs[a].x);
    boxes[i].top = std::min(boxes[i].top, runs[a].top);
    boxes[i].bottom = std::max(boxes[i].bottom, runs[a].bottom);
    topUnseen[i] = topUnseen[i] || runs[a].fromTop;
  }
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    auto& o = boxes[i];
    const double footX = 0.5 * (minX[i] + maxX[i]);
    double hPx, wPx;
    if (!sizesAt(cm, footX, o.bottom - 0.5, kRobotHeight, kMinWidth, hPx, wPx)) continue;
    const double width = maxX[i] - minX[i];
    if (width + image.width / 160.0 < wPx) continue;  // one thin run: a line along the scan line, a post
    if (width > wPx / kMinWidth * kMaxWidth) continue;  // a line just below the boundary, joined to the wall
    // Half a line spacing beyond the outer runs; up by a robot's height from its feet where
    // the object reaches the boundary (its top is not seen), else to its seen top (field
    // above it: e.g. the robot's own shoulder in the bottom camera, with a line behind it).
    const int pad = std::max(2, static_cast<int>(0.5 * wPx));
    o.left = std::max(0, static_cast<int>(minX[i]) - pad);
    o.right = std::min(image.width, static_cast<int>(maxX[i]) + pad + 1);
    // A seen top is known to the vertical lines' sample step (at most height / 60, ScanGrid):
    // the field above it stays out of the box (a line passing above the own shoulder).
    const int topPad = std::max(2, image.height / 60);
    o.top = topUnseen[i] ? std::max(0, std::min(o.top, static_cast<int>(o.bottom - hPx))) : std::max(0, o.top - topPad);
    if (const auto g = cm.pixelToGround({footX, o.bottom - 0.5})) o.footRobot = *g;
    out.obstacles.push_back(o);
  }
  return out;
}

}  // namespace nao
