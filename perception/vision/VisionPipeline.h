#pragma once
// The whole vision for one camera image: scan grid, colour-segmented scan lines, field
// boundary, obstacles, ball, line spots and lines, centre circle, intersections, penalty
// mark, goal box side. Every threshold is computed from the image at hand; the parameters
// below are geometry (field and ball sizes), the same in simulation and on a real field.
#include <map>
#include <string>

#include "perception/CameraModel.h"
#include "perception/FieldDimensions.h"
#include "perception/vision/VisionTypes.h"

namespace nao {

struct VisionResult {
  ScanLineRegions regions;
  FieldBoundary boundary;
  ObstaclesPercept obstacles;
  LinesPercept lines;
  BallPercept ball;
  std::map<std::string, double> stageMs;  // wall time per stage (ms) and "total"
  // Added for debugging and drawing: the pixel of the penalty mark, when found.
  Eigen::Vector2d penaltyMarkImage = Eigen::Vector2d::Zero();
};

// Sizes of what is painted and played with (m), from FieldDimensions.
struct VisionGeometry {
  double lineWidth = 0.05;
  double circleRadius = 0.75;
  double penaltyCrossSize = 0.1;
  double ballRadius = 0.05;
  static VisionGeometry from(const FieldDimensions& d);
};

VisionResult runVision(const CameraImage& image, const CameraMatrix& cm);
VisionResult runVision(const CameraImage& image, const CameraMatrix& cm, const VisionGeometry& geometry);

}  // namespace nao
