#pragma once
// The whole vision for one camera image: scan grid, colour-segmented scan lines, field
// boundary, obstacles, ball, line spots and lines, centre circle, intersections, penalty
// mark, goal box side. A thin wrapper around the camera pipeline's modules
// (perception/vision/CameraPipeline.h), kept for the callers that want one result struct.
// Every threshold is computed from the image at hand; the parameters below are geometry
// (field and ball sizes), the same in simulation and on a real field.
#include <map>
#include <string>

#include "perception/CameraModel.h"
#include "perception/FieldDimensions.h"
#include "perception/vision/VisionTypes.h"
#include "representations/perception/VisionGeometry.h"

namespace nao {

struct VisionResult {
  ScanLineRegions regions;
  FieldBoundary boundary;
  ObstaclesPercept obstacles;
  LinesPercept lines;
  BallPercept ball;
  std::map<std::string, double> stageMs;  // wall time per module (ms, by name) and "total"
  // Added for debugging and drawing: the pixel of the penalty mark, when found.
  Eigen::Vector2d penaltyMarkImage = Eigen::Vector2d::Zero();
};

VisionResult runVision(const CameraImage& image, const CameraMatrix& cm);
VisionResult runVision(const CameraImage& image, const CameraMatrix& cm, const VisionGeometry& geometry);

}  // namespace nao
