#pragma once
// Intersections of field lines, typed as they are on the field (B-Human's L, T, X): where
// two roughly perpendicular lines meet on the ground, each line either passes through the
// point or ends there. An end at the image border (or at an obstacle) may hide the rest of
// the line, so an intersection whose type depends on such an end is not reported. So may a
// piece the line detector missed: an end counts only where the image shows field beyond it
// (white on the line's course beyond the other line's paint makes it open too).
#include <vector>

#include "perception/CameraModel.h"
#include "perception/vision/ColourTests.h"
#include "perception/vision/VisionTypes.h"

namespace nao::vision {

struct IntersectionParams {
  double maxAngleErrorDeg = 25;  // from perpendicular, on the ground
  double maxExtension = 0.35;    // m a line may stop short of the point (thick paint at corners)
  double endMargin = 0.15;       // m: a point this close to a line's end is at its end
  double borderPx = 6;           // a line end this close to the image border is open
  // Beyond an end, samples on the line's course from `beyondFrom` to `beyondTo` m past the
  // point (clear of the other line's paint): more than this share white, the line goes on.
  double beyondFrom = 0.08, beyondTo = 0.24;
  double maxWhiteBeyond = 0.4;
};

// image and field (optional, both or neither): look beyond each end for a missed piece.
std::vector<LinesPercept::Intersection> detectIntersections(const std::vector<LinesPercept::Line>& lines,
                                                             const CameraMatrix& cm,
                                                             const ObstaclesPercept& obstacles,
                                                             const IntersectionParams& params = {},
                                                             const CameraImage* image = nullptr,
                                                             const FieldReference* field = nullptr);

}  // namespace nao::vision
