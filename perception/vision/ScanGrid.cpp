#include "perception/vision/ScanGrid.h"

#include <algorithm>
#include <cmath>

namespace nao {
namespace {

// Grid constants: pure geometry (fractions of the expected line size), not tuned for light.
constexpr double kSpacingPerLineWidth = 1.0;  // vertical (and regular horizontal) line spacing per expected line width
// Horizontal lines find the lines that run up the image (away from the camera). Far away such
// a line is short in the image against its width (a 0.6 m goal box side 3 m away spans about
// two line widths), so extra rows lie between two rows a line's width apart, at most this
// many line heights apart (15 cm of ground along the view: such a line is crossed 4 times).
constexpr double kRowSpacingPerLineHeight = 3.0;
constexpr double kStepPerLineSize = 0.6;      // sample step per expected line thickness along the line
// Every other pixel at least: the 3-pixel smoothing kernel still covers each pixel.
constexpr int kMinStep = 2;
// The robot's own feet on the ground (robot frame, m), excluded from the scan lines.
constexpr double kFootMinX = -0.10, kFootMaxX = 0.14, kFootHalfY = 0.13;

bool onOwnFeet(const CameraMatrix& cm, double px, double py) {
  const auto g = cm.pixelToGround({px, py});
  return g && g->x() > kFootMinX && g->x() < kFootMaxX && std::abs(g->y()) < kFootHalfY;
}

}  // namespace

ScanGrid makeScanGrid(const CameraMatrix& cmIn, int W, int H, double lineWidthM) {
  ScanGrid g;
  g.width = W;
  g.height = H;
  if (W <= 0 || H <= 0) return g;
  // The camera matrix at this resolution (the same field of view).
  CameraMatrix cm = cmIn;
  if (cm.intrinsics.width != W || cm.intrinsics.height != H) {
    const double sx = static_cast<double>(W) / cm.intrinsics.width, sy = static_cast<double>(H) / cm.intrinsics.height;
    cm.intrinsics.fx *= sx;
    cm.intrinsics.cx *= sx;
    cm.intrinsics.fy *= sy;
    cm.intrinsics.cy *= sy;
    cm.intrinsics.width = W;
    cm.intrinsics.height = H;
  }
  // The ray's z (robot frame) is linear in the pixel: rz = a + b px + c py; below the horizon rz < 0.
  const Eigen::Matrix3d R = cm.pose.linear();
  const auto& in = cm.intrinsics;
  const double b = -R(2, 1) / in.fx, c = -R(2, 2) / in.fy;
  const double a = R(2, 0) + R(2, 1) * in.cx / in.fx + R(2, 2) * in.cy / in.fy;
  const double eps = 1e-4;  // rays closer to level than this are "at the horizon"
  // Rows [first, last) of column centre px that look at the ground.
  auto groundRows = [&](double px) -> std::pair<int, int> {
    const double r0 = a + b * px;  // rz at py = 0
    if (std::abs(c) < 1e-12) return r0 < -eps ? std::pair{0, H} : std::pair{H, H};
    const double yh = (-eps - r0) / c;  // rz = -eps at py = yh
    if (c < 0) {                        // upright: the ground is below the horizon
      const int first = std::clamp(static_cast<int>(std::floor(yh - 0.5)) + 1, 0, H);
      return {first, H};
    }
    const int last = std::clamp(static_cast<int>(std::ceil(yh - 0.5)), 0, H);
    return {0, last};
  };

  // Expected line sizes per row (at the centre column), computed every few rows and interpolated.
  g.lineWidthPx.assign(H, 0.f);
  g.lineHeightPx.assign(H, 0.f);
  const double cxc = W / 2.0;
  const auto [centreFirst, centreLast] = groundRows(cxc);
  const Eigen::Vector2d camGround = cm.pose.translation().head<2>();
  auto sizesAt = [&](double py, float& w, float& h) {
    w = h = 0;
    const auto p = cm.pixelToGround({cxc, py});
    if (!p) return false;
    Eigen::Vector2d radial = *p - camGround;
    if (radial.norm() < 1e-6) radial = Eigen::Vector2d::UnitX();
    radial.normalize();
    const Eigen::Vector2d lateral(-radial.y(), radial.x());
    const auto l1 = cm.projectGround(*p + lateral * lineWidthM / 2), l2 = cm.projectGround(*p - lateral * lineWidthM / 2);
    const auto r1 = cm.projectGround(*p + radial * lineWidthM / 2), r2 = cm.projectGround(*p - radial * lineWidthM / 2);
    if (!l1 || !l2 || !r1 || !r2) return false;
    w = static_cast<float>((*l1 - *l2).norm());
    h = static_cast<float>((*r1 - *r2).norm());
    return true;
  };
  constexpr int kRowStride = 4;
  {
    int prevRow = -1;
    float prevW = 0, prevH = 0;
    for (int y = centreFirst; y < centreLast; ++y) {
      if (y != centreFirst && y != centreLast - 1 && (y - centreFirst) % kRowStride != 0) continue;
      float w, h;
      if (!sizesAt(y + 0.5, w, h)) continue;
      g.lineWidthPx[y] = w;
      g.lineHeightPx[y] = h;
      if (prevRow >= 0)
        for (int k = prevRow + 1; k < y; ++k) {
          const float t = static_cast<float>(k - prevRow) / (y - prevRow);
          g.lineWidthPx[k] = prevW + t * (w - prevW);
          g.lineHeightPx[k] = prevH + t * (h - prevH);
        }
      prevRow = y;
      prevW = w;
      prevH = h;
    }
  }

  // The horizon's topmost row below it over the image's width.
  const auto [leftFirst, leftLast] = groundRows(0.5);
  const auto [rightFirst, rightLast] = groundRows(W - 0.5);
  g.horizonY = std::min(leftFirst, rightFirst);
  if (leftFirst >= leftLast && rightFirst >= rightLast) g.horizonY = H;

  // Vertical lines: a hierarchy of spacings minSpacing << level.
  g.minSpacing = std::max(2, W / 160);
  const int maxSpacing = std::max(g.minSpacing, W / 20);
  int maxLevel = 0;
  while ((g.minSpacing << (maxLevel + 1)) <= maxSpacing) ++maxLevel;
  auto required = [&](int y) {
    return std::clamp(g.lineWidthPx[y] * kSpacingPerLineWidth, static_cast<double>(g.minSpacing),
                      static_cast<double>(maxSpacing));
  };
  // endRow[l]: below it, the lines of level l + 1 are dense enough.
  std::vector<int> endRow(maxLevel + 1, H);
  for (int l = 0; l < maxLevel; ++l)
    for (int y = centreFirst; y < centreLast; ++y)
      if (g.lineWidthPx[y] > 0 && required(y) >= (g.minSpacing << (l + 1))) {
        endRow[l] = y;
        break;
      }
  const int n = W / g.minSpacing;
  for (int i = 0; i < n; ++i) {
    int level = 0;
    while (level < maxLevel && ((i >> level) & 1) == 0) ++level;
    if (i == 0) level = maxLevel;
    const int x = i * g.minSpacing + g.minSpacing / 2;
    auto [top, bottom] = groundRows(x + 0.5);
    bottom = std::min(bottom, endRow[level]);
    // The robot's own feet at the bottom of the image (bottom camera looking down).
    if (bottom == H && onOwnFeet(cm, x + 0.5, H - 0.5)) {
      int y = H - 1;
      while (y > top && onOwnFeet(cm, x + 0.5, y - 0.5)) y -= 2;
      bottom = std::max(top, y - 2);
    }
    if (bottom - top < 2) continue;
    g.xs.push_back(x);
    g.topY.push_back(top);
    g.bottomY.push_back(bottom);
    g.levels.push_back(level);
  }

  // Sample rows of the vertical lines.
  const int maxStepY = std::max(2, H / 60);
  for (int y = g.horizonY; y < H;) {
    g.sampleRows.push_back(y);
    const double s = g.lineHeightPx[y] > 0 ? g.lineHeightPx[y] * kStepPerLineSize : 1.0;
    y += std::clamp(static_cast<int>(s), kMinStep, maxStepY);
  }

  // Horizontal lines, from the bottom up.
  const int minSpacingY = std::max(2, H / 120), maxSpacingY = std::max(minSpacingY, H / 15);
  const int maxStepX = std::max(2, W / 80);
  // The regular rows (a line's width apart), and above each of them, up to the next one, extra
  // rows a line's height times kRowSpacingPerLineHeight apart where that is closer (far rows
  // only), none closer than minSpacingY to the next regular row.
  std::vector<int> rows;
  std::vector<char> extra;
  for (int y = H - 1 - maxSpacingY / 4; y >= g.horizonY;) {
    rows.push_back(y);
    extra.push_back(0);
    const int s = static_cast<int>(std::clamp(g.lineWidthPx[y] * kSpacingPerLineWidth, static_cast<double>(minSpacingY),
                                              static_cast<double>(maxSpacingY)));
    const int next = y - s;
    for (int e = y;;) {
      e -= static_cast<int>(std::clamp(g.lineHeightPx[e] * kRowSpacingPerLineHeight, static_cast<double>(minSpacingY),
                                       static_cast<double>(maxSpacingY)));
      if (e < g.horizonY || e - next < minSpacingY) break;
      rows.push_back(e);
      extra.push_back(1);
    }
    y = next;
  }
  std::reverse(rows.begin(), rows.end());
  std::reverse(extra.begin(), extra.end());
  for (std::size_t row = 0; row < rows.size(); ++row) {
    const int y = rows[row];
    // Columns below the horizon: a + b px + c py < -eps.
    double lo = 0, hi = W;
    const double r = a + c * (y + 0.5);
    if (std::abs(b) < 1e-12) {
      if (r >= -eps) continue;
    } else {
      const double px0 = (-eps - r) / b;  // rz = -eps
      if (b > 0) hi = std::min<double>(W, px0);
      else lo = std::max(0.0, px0);
    }
    int left = std::clamp(static_cast<int>(std::ceil(lo - 0.5)), 0, W);
    int right = std::clamp(static_cast<int>(std::floor(hi - 0.5)) + 1, 0, W);
    // Off the own feet: the longest run of columns whose pixel on this row misses them.
    if (onOwnFeet(cm, W / 2.0, y + 0.5) || onOwnFeet(cm, 0.5, y + 0.5) || onOwnFeet(cm, W - 0.5, y + 0.5)) {
      int bestL = 0, bestR = 0, runL = -1;
      for (int x = 0; x <= W; x += 2) {
        const bool free = x < W && !onOwnFeet(cm, x + 0.5, y + 0.5);
        if (free && runL < 0) runL = x;
        if (!free && runL >= 0) {
          if (x - runL > bestR - bestL) bestL = runL, bestR = x;
          runL = -1;
        }
      }
      left = std::max(left, bestL);
      right = std::min(right, bestR);
    }
    if (right - left < 4) continue;
    g.ys.push_back(y);
    g.leftX.push_back(left);
    g.rightX.push_back(right);
    const double s = g.lineWidthPx[y] > 0 ? g.lineWidthPx[y] * kStepPerLineSize : 1.0;
    g.xStep.push_back(std::clamp(static_cast<int>(s), kMinStep, maxStepX));
    g.extraRow.push_back(extra[row]);
  }
  return g;
}

CameraMatrix cameraMatrixForUnknownPose(int width, int height) {
  CameraMatrix cm;
  cm.intrinsics = CameraIntrinsics::fromFovY(width, height);
  const double pitch = cm.intrinsics.fovY() / 2 + M_PI / 180;
  cm.pose = Eigen::Isometry3d::Identity();
  cm.pose.linear() = Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()).toRotationMatrix();
  cm.pose.translation() = Eigen::Vector3d(0, 0, 0.5);
  return cm;
}

}  // namespace nao
