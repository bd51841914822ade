#include "perception/vision/VisionDebug.h"

#include <opencv2/imgproc.hpp>

namespace nao {
namespace {

cv::Scalar classColour(RegionClass c) {
  switch (c) {
    case RegionClass::Field: return {0, 190, 0};
    case RegionClass::White: return {255, 0, 0};
    case RegionClass::Other: return {60, 90, 255};
    default: return {128, 128, 128};
  }
}

}  // namespace

void drawScanLineRegions(cv::Mat& rgb, const ScanLineRegions& regions) {
  if (rgb.empty() || rgb.type() != CV_8UC3) return;
  for (const ScanLine& line : regions.vertical)
    for (const ScanRegion& r : line.regions)
      cv::line(rgb, {line.coord, r.from}, {line.coord, r.to - 1}, classColour(r.cls), 1);
  for (const ScanLine& line : regions.horizontal)
    for (const ScanRegion& r : line.regions)
      cv::line(rgb, {r.from, line.coord}, {r.to - 1, line.coord}, classColour(r.cls), 1);
}

void drawFieldBoundary(cv::Mat& rgb, const FieldBoundary& boundary) {
  if (rgb.empty() || !boundary.valid) return;
  for (std::size_t i = 1; i < boundary.points.size(); ++i)
    cv::line(rgb, cv::Point2d(boundary.points[i - 1].x(), boundary.points[i - 1].y()),
             cv::Point2d(boundary.points[i].x(), boundary.points[i].y()), {255, 230, 0}, 2);
}

void drawObstacles(cv::Mat& rgb, const ObstaclesPercept& obstacles) {
  if (rgb.empty()) return;
  for (const auto& o : obstacles.obstacles)
    cv::rectangle(rgb, {o.left, o.top}, {o.right - 1, o.bottom - 1}, {255, 0, 255}, 2);
}

}  // namespace nao
