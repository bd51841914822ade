#pragma once
// The goal box seen from the side in one image (GoalBoxSidePerceptor): indices into
// FieldLines::lines.
#include "perception/vision/VisionTypes.h"

namespace nao {

struct GoalBoxSidePercept {
  LinesPercept::GoalBoxSide side;
};

}  // namespace nao
