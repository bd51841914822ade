#include "sim/FieldView.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>

#include "robot/Error.h"

namespace nao::sim {

namespace {

constexpr int kShift = 4;              // sub-pixel bits for OpenCV drawing
constexpr double kRobotRadius = 0.15;  // m: a NAO's footprint, roughly
const cv::Scalar kCarpet(30, 125, 40), kLine(245, 245, 245), kGoal(250, 250, 250), kNet(170, 170, 170);
const cv::Scalar kRobot(40, 90, 220), kHeading(255, 255, 255), kBall(255, 140, 0), kBallRim(255, 255, 255);

}  // namespace

cv::Mat drawFieldView(const FieldModel& field, const std::vector<Eigen::Vector3d>& robotPoses,
                      const std::vector<Eigen::Vector3d>& balls, int pixelsPerMetre) {
  if (pixelsPerMetre < 5 || pixelsPerMetre > 1000)
    throw Error("FieldView", "pixelsPerMetre must be in 5..1000, got " + std::to_string(pixelsPerMetre));
  const FieldDimensions& d = field.dims;
  const double ppm = pixelsPerMetre;
  const double cx = d.length / 2 + d.borderStripWidth, cy = d.width / 2 + d.borderStripWidth;
  cv::Mat image(static_cast<int>(std::lround(2 * cy * ppm)), static_cast<int>(std::lround(2 * cx * ppm)), CV_8UC3,
                kCarpet);
  // Field (x, y) -> fixed-point pixel.
  auto px = [&](double x, double y) {
    return cv::Point(static_cast<int>(std::lround((x + cx) * ppm * (1 << kShift))),
                     static_cast<int>(std::lround((cy - y) * ppm * (1 << kShift))));
  };
  auto len = [&](double metres) { return static_cast<int>(std::lround(metres * ppm * (1 << kShift))); };
  const int lineThickness = std::max(1, static_cast<int>(std::lround(d.lineWidth * ppm)));

  for (const FieldLine& l : field.lines)
    cv::line(image, px(l.from.x(), l.from.y()), px(l.to.x(), l.to.y()), kLine, lineThickness, cv::LINE_AA, kShift);
  cv::circle(image, px(field.centerCircleCenter.x(), field.centerCircleCenter.y()), len(field.centerCircleRadius),
             kLine, lineThickness, cv::LINE_AA, kShift);
  const double h = d.penaltyCrossSize / 2;
  auto cross = [&](const Eigen::Vector2d& p, bool both) {
    cv::line(image, px(p.x() - h, p.y()), px(p.x() + h, p.y()), kLine, lineThickness, cv::LINE_AA, kShift);
    if (both) cv::line(image, px(p.x(), p.y() - h), px(p.x(), p.y() + h), kLine, lineThickness, cv::LINE_AA, kShift);
  };
  for (const Eigen::Vector2d& p : field.penaltyCrosses) cross(p, true);
  cross(field.centerMark, false);

  // Goals: net outline behind the goal line, posts as white dots.
  const double py = d.goalInnerWidth / 2 + d.goalPostDiameter / 2;
  for (double side : {-1.0, 1.0}) {
    const double gx = side * d.length / 2, bx = side * (d.length / 2 + d.goalDepth);
    cv::line(image, px(gx, py), px(bx, py), kNet, 1, cv::LINE_AA, kShift);
    cv::line(image, px(bx, py), px(bx, -py), kNet, 1, cv::LINE_AA, kShift);
    cv::line(image, px(bx, -py), px(gx, -py), kNet, 1, cv::LINE_AA, kShift);
    for (double sy : {-1.0, 1.0})
      cv::circle(image, px(gx, sy * py), std::max(len(d.goalPostDiameter / 2), 2 << kShift), kGoal, cv::FILLED,
                 cv::LINE_AA, kShift);
  }

  for (std::size_t i = 0; i < robotPoses.size(); ++i) {
    const Eigen::Vector3d& r = robotPoses[i];
    if (!r.allFinite()) continue;
    const int radius = std::max(len(kRobotRadius), 4 << kShift);
    cv::circle(image, px(r.x(), r.y()), radius, kRobot, cv::FILLED, cv::LINE_AA, kShift);
    const double reach = std::max(kRobotRadius * 1.6, 8 / ppm);
    cv::line(image, px(r.x(), r.y()), px(r.x() + reach * std::cos(r.z()), r.y() + reach * std::sin(r.z())), kHeading,
             std::max(1, lineThickness / 2), cv::LINE_AA, kShift);
    const cv::Point label = px(r.x() + kRobotRadius, r.y() - kRobotRadius);
    cv::putText(image, std::to_string(i), cv::Point(label.x >> kShift, label.y >> kShift), cv::FONT_HERSHEY_SIMPLEX,
                std::max(0.3, ppm / 160), kHeading, 1, cv::LINE_AA);
  }
  for (const Eigen::Vector3d& b : balls) {
    if (!b.allFinite()) continue;
    const int radius = std::max(len(0.05), 3 << kShift);
    cv::circle(image, px(b.x(), b.y()), radius, kBall, cv::FILLED, cv::LINE_AA, kShift);
    cv::circle(image, px(b.x(), b.y()), radius, kBallRim, 1, cv::LINE_AA, kShift);
  }
  return image;
}

void drawEstimates(cv::Mat& view, const FieldModel& field, const EstimateOverlay& estimate, int pixelsPerMetre) {
  const FieldDimensions& d = field.dims;
  const double ppm = pixelsPerMetre;
  const double cx = d.length / 2 + d.borderStripWidth, cy = d.width / 2 + d.borderStripWidth;
  auto px = [&](double x, double y) {
    return cv::Point(static_cast<int>(std::lround((x + cx) * ppm * (1 << kShift))),
                     static_cast<int>(std::lround((cy - y) * ppm * (1 << kShift))));
  };
  auto len = [&](double metres) { return static_cast<int>(std::lround(metres * ppm * (1 << kShift))); };
  const cv::Scalar kEstimate(255, 230, 0), kModelBall(255, 60, 200);
  if (estimate.pose && estimate.pose->allFinite()) {
    const Eigen::Vector3d& r = *estimate.pose;
    const Eigen::Matrix2d c = 0.5 * (estimate.positionCovariance + estimate.positionCovariance.transpose());
    if (c.allFinite()) {
      // The 2-sigma ellipse: axes along the covariance's eigenvectors.
      const double a = c(0, 0), b = c(0, 1), e = c(1, 1);
      const double mean = 0.5 * (a + e), diff = std::sqrt(0.25 * (a - e) * (a - e) + b * b);
      const double major = 2 * std::sqrt(std::max(0.0, mean + diff)), minor = 2 * std::sqrt(std::max(0.0, mean - diff));
      const double angle = 0.5 * std::atan2(2 * b, a - e) * 180 / M_PI;
      if (major * ppm >= 1)
        cv::ellipse(view, px(r.x(), r.y()), cv::Size(len(major), std::max(len(minor), 1)), -angle, 0, 360, kEstimate, 1,
                    cv::LINE_AA, kShift);
    }
    const int radius = std::max(len(kRobotRadius), 4 << kShift);
    cv::circle(view, px(r.x(), r.y()), radius, kEstimate, 2, cv::LINE_AA, kShift);
    const double reach = std::max(kRobotRadius * 1.6, 8 / ppm);
    cv::line(view, px(r.x(), r.y()), px(r.x() + reach * std::cos(r.z()), r.y() + reach * std::sin(r.z())), kEstimate, 2,
             cv::LINE_AA, kShift);
  }
  if (estimate.ball && estimate.ball->allFinite())
    cv::circle(view, px(estimate.ball->x(), estimate.ball->y()), std::max(len(0.08), 4 << kShift), kModelBall, 2,
               cv::LINE_AA, kShift);
}

namespace {
cv::Point fieldPixel(const FieldModel& field, const Eigen::Vector2d& p, int pixelsPerMetre) {
  const FieldDimensions& d = field.dims;
  const double cx = d.length / 2 + d.borderStripWidth, cy = d.width / 2 + d.borderStripWidth;
  return cv::Point(static_cast<int>(std::lround((p.x() + cx) * pixelsPerMetre * (1 << kShift))),
                   static_cast<int>(std::lround((cy - p.y()) * pixelsPerMetre * (1 << kShift))));
}
}  // namespace

void drawPath(cv::Mat& view, const FieldModel& field, const std::vector<Eigen::Vector2d>& points, const cv::Scalar& rgb,
              int pixelsPerMetre) {
  for (std::size_t i = 1; i < points.size(); ++i)
    if (points[i - 1].allFinite() && points[i].allFinite())
      cv::line(view, fieldPixel(field, points[i - 1], pixelsPerMetre), fieldPixel(field, points[i], pixelsPerMetre), rgb,
               2, cv::LINE_AA, kShift);
}

void drawMarker(cv::Mat& view, const FieldModel& field, const Eigen::Vector2d& point, const cv::Scalar& rgb,
                const std::string& label, int pixelsPerMetre) {
  if (!point.allFinite()) return;
  const cv::Point c = fieldPixel(field, point, pixelsPerMetre);
  const int arm = 6 << kShift;
  cv::line(view, c - cv::Point(arm, arm), c + cv::Point(arm, arm), rgb, 2, cv::LINE_AA, kShift);
  cv::line(view, c - cv::Point(arm, -arm), c + cv::Point(arm, -arm), rgb, 2, cv::LINE_AA, kShift);
  if (!label.empty())
    cv::putText(view, label, cv::Point((c.x >> kShift) + 8, (c.y >> kShift) - 8), cv::FONT_HERSHEY_SIMPLEX, 0.45, rgb, 1,
                cv::LINE_AA);
}

}  // namespace nao::sim
