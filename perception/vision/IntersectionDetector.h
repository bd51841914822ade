#pragma once
// Intersections of field lines, typed as they are on the field (B-Human's L, T, X): where
// two roughly perpendicular lines meet on the ground, each line either passes through the
// point or ends there. An end at the image border (or at an obstacle) may hide the rest of
// the line, so an intersection whose type depends on such an end is not reported.
#include <vector>

#include "perception/CameraModel.h"
#include "perception/vision/VisionTypes.h"

namespace nao::vision {

struct IntersectionParams {
  double maxAngleErrorDeg = 25;  // from perpendicular, on the ground
  double maxExtension = 0.35;    // m a line may stop short of the point (thick paint at corners)
  double endMargin = 0.15;       // m: a point this close to a line's end is at its end
  double borderPx = 6;           // a line end this close to the image border is open
};

std::vector<LinesPercept::Intersection> detectIntersections(const std::vector<LinesPercept::Line>& lines,
                                                             const CameraMatrix& cm,
                                                             const ObstaclesPercept& obstacles,
                                                             const IntersectionParams& params = {});

}  // namespace nao::vision
