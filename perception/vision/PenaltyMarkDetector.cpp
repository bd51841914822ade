#include "perception/vision/PenaltyMarkDetector.h"

#include <cmath>

#include "perception/vision/ColourTests.h"
#include "perception/vision/LineDetector.h"

namespace nao::vision {
namespace {

double segmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  const double l2 = d.squaredNorm();
  const double t = l2 > 0 ? std::clamp((p - a).dot(d) / l2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}

// The run of pixels brighter than `threshold` through (x, y) along a row (dx = 1) or a
// column (dy = 1): [lo, hi) in pixel indices.
std::pair<int, int> brightRun(const CameraImage& img, int x, int y, int dx, int dy, double threshold, int maxLen) {
  auto bright = [&](int xx, int yy) {
    return xx >= 0 && yy >= 0 && xx < img.width && yy < img.height && img.y(xx, yy) > threshold;
  };
  int lo = 0, hi = 1;
  while (lo > -maxLen && bright(x + (lo - 1) * dx, y + (lo - 1) * dy)) --lo;
  while (hi < maxLen && bright(x + hi * dx, y + hi * dy)) ++hi;
  const int base = dx ? x : y;
  return {base + lo, base + hi};
}

}  // namespace

std::optional<Eigen::Vector2d> detectPenaltyMark(const CameraImage& image, const ScanLineRegions& regions,
                                                 const FieldReference& field,
                                                 const std::vector<LinesPercept::Line>& lines,
                                                 const ObstaclesPercept& obstacles, const CameraMatrix& cm,
                                                 const PenaltyMarkParams& params, Eigen::Vector2d* imagePos,
                                                 const BallPercept* ball) {
  if (!field.valid) return std::nullopt;
  const Eigen::Vector2d foot = cm.pose.translation().head<2>();
  for (const ScanLine& sl : regions.vertical) {
    for (const ScanRegion& r : sl.regions) {
      if (!field.isWhiteRegion(r) || r.from <= sl.start) continue;
      const Eigen::Vector2d px(sl.coord + 0.5, 0.5 * (r.from + r.to));
      if (obstacles.contains(px.x(), px.y())) continue;
      if (ball && ball->seen && (px - ball->image).norm() < 1.5 * ball->radiusPx + 2) continue;
      GroundScale gs = groundScale(cm, px, params.size);
      if (!gs.valid || (gs.ground - foot).norm() > params.maxDistance) continue;
      const double len = r.to - r.from;
      if (len < params.minSizeRatio * gs.alongPx || len > params.maxSizeRatio * gs.alongPx + 1.5) continue;
      bool nearLine = false;
      for (const auto& l : lines) nearLine = nearLine || segmentDistance(gs.ground, l.from, l.to) < params.lineClearance;
      if (nearLine) continue;
      // Half way between the blob and the field around it.
      const double threshold = 0.5 * (r.colour.y + 0.5 * (field.yMin + field.yMax));
      const int maxLen = static_cast<int>(3 * std::max(gs.acrossPx, gs.alongPx)) + 4;
      const auto [x0, x1] = brightRun(image, sl.coord, static_cast<int>(px.y()), 1, 0, threshold, maxLen);
      const double w = x1 - x0;
      if (w < params.minSizeRatio * gs.acrossPx || w > params.maxSizeRatio * gs.acrossPx + 1.5) continue;
      const int cx = (x0 + x1) / 2;
      const auto [y0, y1] = brightRun(image, cx, static_cast<int>(px.y()), 0, 1, threshold, maxLen);
      const double h = y1 - y0;
      const Eigen::Vector2d centre(0.5 * (x0 + x1), 0.5 * (y0 + y1));
      gs = groundScale(cm, centre, params.size);
      if (!gs.valid || h < params.minSizeRatio * gs.alongPx || h > params.maxSizeRatio * gs.alongPx + 1.5) continue;
      // The field all around, on the ground, on two rings: a line's end, a junction or a piece
      // of the circle that the line detector missed has white running out across them, a cross
      // has none. On the inner ring a line (5 cm) always covers a sample (3 cm apart); on the
      // outer one (5.2 cm apart) it may fall between two. Denser outer rings (48 samples, or
      // 40 at 0.25 m) lost the real cross of image 00123 (4 samples off the field there).
      bool clear = true;
      for (const double radius : params.ringRadii) {
        constexpr int kRing = 36;
        int inView = 0, notField = 0;
        for (int k = 0; k < kRing; ++k) {
          const double a = 2 * M_PI * k / kRing;
          const auto q = cm.projectGround(gs.ground + radius * Eigen::Vector2d(std::cos(a), std::sin(a)));
          if (!q || !insideImage(image, q->x(), q->y(), 1)) continue;
          ++inView;
          const PixelColour c = sampleColour(image, q->x(), q->y());
          notField += !(field.isField(c) && c.y < threshold);
        }
        clear = clear && inView >= params.minRingInView * kRing && notField <= params.maxRingMisses;
      }
      if (!clear) continue;
      if (imagePos) *imagePos = centre;
      return gs.ground;
    }
  }
  return std::nullopt;
}

}  // namespace nao::vision
