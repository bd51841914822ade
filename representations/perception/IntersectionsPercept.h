#pragma once
// L, T and X intersections of the field lines of one image (IntersectionPerceptor); line1
// and line2 index FieldLines::lines.
#include <vector>

#include "perception/vision/VisionTypes.h"

namespace nao {

struct IntersectionsPercept {
  std::vector<LinesPercept::Intersection> intersections;
};

}  // namespace nao
