#pragma once
// Finds the goal box seen from the side in the image, without the (still wrong) projection
// (B-Human 2021, section 3): "a short line that connects two long lines", which on an SPL
// field is true of the goal box only. Works on painted-line segments in the image, from one of
// two sources (a small switch):
//   - paintLineSegments(): OpenCV's line segment detector (LSD) on the grayscale image below
//     the horizon; LSD gives the paint edges, two antiparallel edges with the bright side
//     between them become one painted line, and collinear pieces are merged;
//   - segmentsFromLinesPercept(): the vision pipeline's lines (perception/vision).
// The topology test is image-only: a segment whose two ends each meet another line (at an
// angle) that runs on from there, at least one of them away from the camera (up the image),
// and that do not cross before their visible ends. The projection is used afterwards only to
// reject implausible finds.
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "perception/CameraModel.h"
#include "perception/calibration/HoughRefiner.h"
#include "perception/vision/VisionTypes.h"

namespace nao::calibration {

struct SegmentOptions {
  double minEdgeLengthPx = 10;     // LSD edges shorter than this are ignored
  double maxPairAngleDeg = 15;     // two edges of one paint line (they converge in perspective)
  double minWidthPx = 1.5, maxWidthPx = 60;
  double minOverlap = 0.3;         // of the shorter edge, along the line
  double mergeAngleDeg = 2.5;      // collinear pieces of one line
  double mergeOffsetPx = 2.5;      // (plus a fraction of the width)
  double horizonMarginPx = 40;     // segments this far above the (uncalibrated) horizon still count
};

// Painted-line segments of a grayscale image (CV_8U); only below `horizon` (minus the margin)
// when given.
std::vector<ImageSegment> paintLineSegments(const cv::Mat& gray, const std::optional<ImageLine>& horizon,
                                            const SegmentOptions& options = {});

// The vision pipeline's lines as segments. Their width comes from the line width projected
// with `cm` at the segment's middle (the pipeline does not report it).
std::vector<ImageSegment> segmentsFromLinesPercept(const std::vector<LinesPercept::Line>& lines, const CameraMatrix& cm,
                                                   double lineWidth);

struct FinderOptions {
  double minShortLengthPx = 25;
  double minAngleDeg = 15;         // between the short line and a long one, in the image
  // Beyond the lines' half widths: the vision's and LSD's lines stop short of an L corner (its
  // junction, worn paint); chosen on the real goal-box frames (docs/vision/real/README.md).
  double junctionSlackPx = 30;
  double minRunOnPx = 20;          // each long line runs at least this far beyond the short line
  double borderPx = 3;             // a short line touching the border is cut off: not a find
};

struct GoalBoxSideDetection {
  bool found = false;
  std::string reason;                       // why not
  ImageSegment shortLine, longLine1, longLine2;
  Eigen::Vector2d junction1 = Eigen::Vector2d::Zero(), junction2 = Eigen::Vector2d::Zero();  // short meets long1, long2
  int candidates = 0;                       // how many configurations passed the test
};

// Every configuration that passes, best first (longest short line, longest run-on).
std::vector<GoalBoxSideDetection> findGoalBoxSideCandidates(const std::vector<ImageSegment>& lines, int width,
                                                             int height, const FinderOptions& options = {});
// The best one, or found = false with the reason.
GoalBoxSideDetection findGoalBoxSide(const std::vector<ImageSegment>& lines, int width, int height,
                                     const FinderOptions& options = {});

}  // namespace nao::calibration
