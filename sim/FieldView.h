#pragma once
// A top-down schematic of the field for logs and reports: green carpet, white lines, goals,
// robots (circle + heading, numbered from 0) and balls. Field x points right, y up.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "perception/FieldDimensions.h"

namespace nao::sim {

// CV_8UC3 in RGB order (write it with writePng from sim/ImageIO.h), covering the carpet
// (field plus border strip) at pixelsPerMetre. robotPoses: (x, y, theta); balls: (x, y, z).
// Throws nao::Error("FieldView", ...) for pixelsPerMetre outside 5..1000.
cv::Mat drawFieldView(const FieldModel& field, const std::vector<Eigen::Vector3d>& robotPoses,
                      const std::vector<Eigen::Vector3d>& balls, int pixelsPerMetre = 80);

// What the robot program believes, drawn over a drawFieldView picture of the same field and
// scale: the estimated pose (a ring with its heading) with its 2-sigma position ellipse
// (covariance of x, y in m^2), and the modelled ball (a ring).
struct EstimateOverlay {
  std::optional<Eigen::Vector3d> pose;  // (x, y, theta)
  Eigen::Matrix2d positionCovariance = Eigen::Matrix2d::Zero();
  std::optional<Eigen::Vector2d> ball;  // field frame
};
void drawEstimates(cv::Mat& view, const FieldModel& field, const EstimateOverlay& estimate, int pixelsPerMetre = 80);

// A walked path (field points in order) and a labelled cross (a report against its truth),
// over a drawFieldView picture of the same field and scale. Colours in RGB.
void drawPath(cv::Mat& view, const FieldModel& field, const std::vector<Eigen::Vector2d>& points, const cv::Scalar& rgb,
              int pixelsPerMetre = 80);
void drawMarker(cv::Mat& view, const FieldModel& field, const Eigen::Vector2d& point, const cv::Scalar& rgb,
                const std::string& label, int pixelsPerMetre = 80);

}  // namespace nao::sim
