#pragma once
// Line spots of one image with their chains and straight segments (LineSpotProvider): what
// the circle and the lines are fitted to.
#include "perception/vision/LineDetector.h"

namespace nao {

struct LineSpots : vision::LineCandidates {};

}  // namespace nao
