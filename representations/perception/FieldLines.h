#pragma once
// The straight field lines seen in one image (LinePerceptor).
#include <vector>

#include "perception/vision/VisionTypes.h"

namespace nao {

struct FieldLines {
  std::vector<LinesPercept::Line> lines;  // image ends (px) and robot-frame ends (m)
};

}  // namespace nao
