#pragma once
// The centre circle in one image (CirclePerceptor).
#include <vector>

#include "perception/vision/VisionTypes.h"

namespace nao {

struct CirclePercept {
  LinesPercept::Circle circle;      // centre in the robot frame (m)
  std::vector<char> spotsOnCircle;  // per LineSpots::spots: 1 on the found circle (not a line)
};

}  // namespace nao
