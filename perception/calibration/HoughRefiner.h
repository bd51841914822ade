#pragma once
// Refines a roughly located painted line to sub-pixel precision (B-Human 2021, section 3: "the
// lines ... are refined by a Hough transform on a Sobel grayscale image").
//   1. Sobel gradients of the grayscale (Y) image.
//   2. In a band around the coarse line, the gradient maxima across the line (each at its
//      sub-pixel position) vote with their gradient into a fine (angle, distance) Hough
//      accumulator near the coarse line; votes are split by polarity, so the dark-to-bright and
//      the bright-to-dark paint edge give two peaks. Each peak, interpolated between bins, is one
//      paint edge. (Whole pixels voting at their centres would let an axis-parallel line collect
//      entire pixel rows and beat the true, slightly slanted edge.)
//   3. Sub-pixel edge points: along each image column (row, for steep lines) the gradient
//      across the edge peaks at the edge; a parabola through the peak and its two neighbours
//      places it to a fraction of a pixel. A total-least-squares line through the points near
//      the Hough line (outliers dropped; leaning to the intact paint, since wear only takes paint
//      away) is the refined edge. This is where sub-pixel pays: the
//      rendered edges are aliased steps, and hundreds of points average their jags away.
// Stretches near junctions (where other lines' paint interrupts the edges) and near the image
// border are left out; too few edge points along the rest means the line is occluded.
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "perception/calibration/CalibrationSample.h"

namespace nao::calibration {

// A painted line's centre as found in the image (coarse), with its apparent width.
struct ImageSegment {
  Eigen::Vector2d from = Eigen::Vector2d::Zero(), to = Eigen::Vector2d::Zero();  // pixels
  double widthPx = 0;   // distance between the paint edges, across the segment
  double length() const { return (to - from).norm(); }
  Eigen::Vector2d direction() const { return (to - from).normalized(); }
};

// A point along a line near which edges are not measured (a junction with another line).
struct Exclusion {
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  double radiusPx = 0;
};

struct HoughRefinerOptions {
  double angleRangeDeg = 8.0;     // Hough search around the coarse angle, +- (edges converge in perspective)
  double angleStepDeg = 0.1;
  double rhoStepPx = 0.25;
  double bandMarginPx = 4;        // beyond the coarse paint edges
  double borderPx = 3;            // image border left out
  double maxResidualPx = 0.6;     // edge points farther from the fitted edge are outliers
  double paintSideWeight = 0.1;   // an edge point into the paint from the fit counts this, one out of it 1 - this (worn paint)
  double minCoverage = 0.6;       // of the usable stretch with edge points, per edge ...
  double minCoverageSpanned = 1;  // ... or this much where the edge points reach both ends (a worn
  double minSpan = 0.85;          //     stretch between them): span of the scanned stretch, per edge
  int minPoints = 12;             // per edge
  double minStrengthRatio = 0.3;  // an edge point's gradient vs the median along the edge
  double minGreennessStep = 0.15;  // grass side minus paint side
  double colourOffsetPx = 2.5;     // how far from the edge the two sides are sampled (at most)
};

// Sobel gradients (CV_32F) of a grayscale image, and optionally the image's greenness
// ((G - max(R, B)) / Y, CV_32F): grass is green, paint is not, in sun and in shadow and under
// warm or cold light alike. With it, an edge point counts only if its darker side is grass and
// its brighter side paint, so shadow boundaries (grass to grass, or across the paint) do not
// pull the edges.
struct GradientImage {
  cv::Mat gx, gy;
  cv::Mat greenness;  // empty: no colour check
  static GradientImage sobel(const cv::Mat& gray);  // CV_8U or CV_32F
  int width() const { return gx.cols; }
  int height() const { return gx.rows; }
};

struct RefinedLine {
  bool ok = false;
  std::string reason;           // why not
  LineMeasurement measurement;  // edgeA: the edge on the coarse line's left normal side
  double coverage = 0;          // the lower of the two edges'
  double span = 0;              // the lower of the two edges': the edge points' extent along the stretch
};

RefinedLine refineLine(const GradientImage& gradients, const ImageSegment& coarse,
                       const std::vector<Exclusion>& exclusions, const HoughRefinerOptions& options = {});

}  // namespace nao::calibration
