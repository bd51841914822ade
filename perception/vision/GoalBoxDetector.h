#pragma once
// The goal box seen from the side (the calibration position): a short line that joins two
// long lines, the goal box's side line between the goal line and the goal box's front line.
// Found in the image alone, so that a wrong camera matrix (what the calibration corrects)
// cannot hide it.
#include <vector>

#include "perception/vision/VisionTypes.h"

namespace nao::vision {

struct GoalBoxParams {
  double minShortPx = 12;       // image length of the short line
  double longRatio = 1.3;       // each long line at least this much longer than the short one
  double minAngleDeg = 20;      // between the short line and each long line, in the image
  double joinTolerance = 0.25;  // of the short line's length (at least joinTolerancePx)
  double joinTolerancePx = 8;
  double borderPx = 4;          // a short line ending this close to the image border is cut
};

// Of several candidates (the penalty area's side line also joins two long lines) the one
// with the shortest short line is the goal box.
LinesPercept::GoalBoxSide detectGoalBoxSide(const std::vector<LinesPercept::Line>& lines, int width, int height,
                                            const GoalBoxParams& params);

}  // namespace nao::vision

namespace nao {
// The entry point the calibration uses (default parameters).
LinesPercept::GoalBoxSide detectGoalBoxSide(const std::vector<LinesPercept::Line>& lines, int width, int height);
}  // namespace nao
