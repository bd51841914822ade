#pragma once
// From one camera image and the joint angles / IMU angles at its capture time to a calibration
// sample, or to the reason there is none: goal box not found, occluded, or implausible.
//   1. painted-line segments (the vision pipeline's lines, or LSD below the uncalibrated
//      horizon), 2. the goal box side found image-only (GoalBoxFinder),
//   3. each of its three lines refined by Hough + sub-pixel fit (HoughRefiner), away from the
//      junctions, 4. sanity checks with the uncalibrated projection: the refined lines must
//      look roughly like the goal box on the ground (right angles, depth) -- loose enough for
//      several degrees of miscalibration, tight enough to throw out other line pairs.
// Last, where no source gives a sample, the vision's sub-pixel centre lines stand for the
// refined edges (ExtractionOptions::visionCentreLines), with the same checks.
#include <optional>
#include <string>
#include <vector>

#include "perception/CameraCalibration.h"
#include "perception/calibration/CalibrationSample.h"
#include "perception/calibration/GoalBoxFinder.h"
#include "perception/calibration/HoughRefiner.h"
#include "perception/vision/VisionTypes.h"
#include "robot/CameraImage.h"

namespace nao::calibration {

// Where the painted-line segments come from: OpenCV's LSD alone (the options' default), the
// vision pipeline first (perception/vision: its lines and its goal box finder, then this finder
// on its lines) falling back to LSD, or LsdThenVision (the robot program's, Calibrator.lines):
// LSD; where it gives no sample, the vision's lines; then both together. LSD goes first because
// it measures better on the simulator's views: over 30 simulated trials (seed 5) the vision-first
// source gave 95th-percentile errors up to 0.10 deg and 2 refused solutions, LSD alone 0.02 deg
// and none (the coarse segments decide which paint edges the refinement locks on to). The
// fallbacks are for real images, where each source tends to miss a different one of the three
// lines (LSD the thin far goal line, the vision the short side line): docs/vision/real/.
enum class LineSource { Lsd, Vision, LsdThenVision };
// "lsd", "vision", "lsd+vision" (Calibrator.lines); throws nao::Error(where, ...) otherwise.
LineSource lineSourceFromName(const std::string& name, const std::string& where);

struct ExtractionOptions {
  LineSource source = LineSource::Lsd;
  SegmentOptions segments;
  FinderOptions finder;
  HoughRefinerOptions hough;
  double goalBoxDepth = 0.6;          // m (field.goalBoxAreaLength)
  double lineWidth = 0.05;            // m
  double junctionMarginPx = 6;        // around junctions, beyond the crossing line's paint
  // Plausibility with the uncalibrated projection.
  double maxAngleErrorDeg = 30;       // each right angle
  double minDepthRatio = 0.5, maxDepthRatio = 1.8;  // measured depth / goal box depth
  double maxFitRmsPx = 0.6;           // edge points about a refined edge
  // The points that stand for each edge lie at least this far below the uncalibrated horizon
  // (well beyond the few degrees the calibration moves it) ...
  double minDepressionDeg = 10;
  // ... or, the long lines only and where no candidate gives a sample so, this far: real frames
  // that look along the goal line have the box's long lines 2-8 deg below the horizon. The short
  // line keeps minDepressionDeg: with it also allowed nearer, the box's far side (the near one
  // missed by the finder) gave 7 of 39 real frames a sample off the labelled lines
  // (docs/vision/real/).
  double longLinesFallbackDepressionDeg = 4;
  double minClippedLengthPx = 15;
  // Goal box candidates tried, best first. On the real goal-box frames the right one was 5th
  // to 8th where far lines gave more junctions (docs/vision/real/README.md).
  int maxCandidates = 8;
  // Last, where nothing else gives a sample: the vision's lines themselves as the measurement
  // (their sub-pixel centre lines instead of the paint edges), the goal box found among them
  // down to this angle between the short and a long line in the image, with a piece of the
  // short line this long (its junctions still finder.minShortLengthPx apart).
  bool visionCentreLines = true;
  double visionCentreMinAngleDeg = 10;
  double visionCentreMinShortPx = 15;
};

struct ExtractionResult {
  std::optional<CalibrationSample> sample;
  std::string reason;                     // when there is no sample
  std::vector<ImageSegment> segments;     // what the finder worked on
  std::string source;                     // of the segments that gave the sample: "vision", "lsd", "vision+lsd" or "vision centre lines"
  GoalBoxSideDetection detection;
};

// The grayscale (Y) channel of a YUYV image as CV_8U.
cv::Mat grayFromYuyv(const CameraImage& image);
// How much greener than red or blue a pixel is, relative to its luminance (CV_32F, 3x3
// smoothed): clearly positive on grass, about zero or negative on paint, in sun, in shadow
// and under warm or cold light.
cv::Mat greenness(const CameraImage& image);

// current: the offsets the robot uses now (the uncalibrated zero, usually) for the horizon
// and the sanity checks. visionLines: the vision pipeline's lines of this image, if it already
// ran (else it runs here when options.source is Vision).
ExtractionResult extractSample(const CameraImage& image, const JointArray& joints, const Eigen::Vector2d& imuAngle,
                               const CameraIntrinsics& intrinsics, const CameraCalibration& current = {},
                               const ExtractionOptions& options = {},
                               const std::vector<LinesPercept::Line>* visionLines = nullptr);
// The same for a recorded image with the robot's own camera matrix of the time (no joint
// angles): the sample carries that pose (CalibrationSample::cameraPose). The matrix's
// intrinsics must be for the image's size.
ExtractionResult extractSample(const CameraImage& image, const CameraMatrix& recorded, const ExtractionOptions& options = {},
                               const std::vector<LinesPercept::Line>* visionLines = nullptr);

}  // namespace nao::calibration
