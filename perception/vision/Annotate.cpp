#include "perception/vision/Annotate.h"

#include <opencv2/imgproc.hpp>

#include "perception/vision/VisionDebug.h"

namespace nao {
namespace {

cv::Point pt(const Eigen::Vector2d& p, int s) { return cv::Point(static_cast<int>(p.x() * s), static_cast<int>(p.y() * s)); }

}  // namespace

cv::Mat annotateVision(const cv::Mat& rgb, const VisionResult& r, const CameraMatrix& cm, int scale) {
  cv::Mat base = rgb.clone();
  drawScanLineRegions(base, r.regions);
  cv::Mat out;
  if (scale > 1)
    cv::resize(base, out, cv::Size(), scale, scale, cv::INTER_NEAREST);
  else
    out = base;
  const int s = std::max(1, scale);
  // Colours in RGB order.
  const cv::Scalar yellow(255, 230, 0), cyan(0, 230, 255), magenta(255, 0, 255), orange(255, 140, 0),
      red(255, 0, 0), blue(40, 90, 255), black(0, 0, 0);
  if (r.boundary.valid)
    for (std::size_t i = 1; i < r.boundary.points.size(); ++i)
      cv::line(out, pt(r.boundary.points[i - 1], s), pt(r.boundary.points[i], s), yellow, 1);
  for (const auto& o : r.obstacles.obstacles)
    cv::rectangle(out, cv::Point(o.left * s, o.top * s), cv::Point(o.right * s, o.bottom * s), orange, 1);
  for (const auto& l : r.lines.lines) {
    for (const auto& p : l.spots) cv::circle(out, pt(p, s), 1 + s / 2, blue, -1);
    cv::line(out, pt(l.imageFrom, s), pt(l.imageTo, s), red, 1 + s / 2);
  }
  if (r.lines.circle.found) {
    std::vector<cv::Point> poly;
    for (int k = 0; k <= 72; ++k) {
      const double a = 2 * M_PI * k / 72;
      const auto p = cm.projectGround(r.lines.circle.centre + r.lines.circle.radius * Eigen::Vector2d(std::cos(a), std::sin(a)));
      if (p && p->x() > -2000 && p->x() < 4000 && p->y() > -2000 && p->y() < 4000) {
        poly.push_back(pt(*p, s));
      } else {
        if (poly.size() > 1) cv::polylines(out, poly, false, magenta, 1 + s / 2);
        poly.clear();
      }
    }
    if (poly.size() > 1) cv::polylines(out, poly, false, magenta, 1 + s / 2);
  }
  for (const auto& x : r.lines.intersections) {
    const char* name = x.type == LinesPercept::Intersection::Type::L ? "L" : x.type == LinesPercept::Intersection::Type::T ? "T" : "X";
    cv::circle(out, pt(x.image, s), 4 * s, cyan, 1 + s / 2);
    cv::putText(out, name, pt(x.image, s) + cv::Point(5 * s, -5 * s), cv::FONT_HERSHEY_SIMPLEX, 0.45 * s, cyan, 1 + s / 2);
  }
  if (r.lines.penaltyMark) {
    const cv::Point c = pt(r.penaltyMarkImage, s);
    cv::drawMarker(out, c, magenta, cv::MARKER_CROSS, 12 * s, 1 + s / 2);
  }
  if (r.lines.goalBoxSide.found) {
    const auto& l = r.lines.lines[r.lines.goalBoxSide.shortLine];
    cv::line(out, pt(l.imageFrom, s), pt(l.imageTo, s), cyan, 2 + s);
  }
  if (r.ball.seen) {
    cv::circle(out, pt(r.ball.image, s), static_cast<int>(r.ball.radiusPx * s), black, 2 + s / 2);
    cv::circle(out, pt(r.ball.image, s), static_cast<int>(r.ball.radiusPx * s), orange, 1 + s / 2);
  }
  return out;
}

}  // namespace nao
