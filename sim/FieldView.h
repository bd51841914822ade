#pragma once
// A top-down schematic of the field for logs and reports: green carpet, white lines, goals,
// robots (circle + heading, numbered from 0) and balls. Field x points right, y up.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "perception/FieldDimensions.h"

namespace nao::sim {

// CV_8UC3 in RGB order (write it with writePng from sim/ImageIO.h), covering the carpet
// (field plus border strip) at pixelsPerMetre. robotPoses: (x, y, theta); balls: (x, y, z).
// Throws nao::Error("FieldView", ...) for pixelsPerMetre outside 5..1000.
cv::Mat drawFieldView(const FieldModel& field, const std::vector<Eigen::Vector3d>& robotPoses,
                      const std::vector<Eigen::Vector3d>& balls, int pixelsPerMetre = 80);

}  // namespace nao::sim
