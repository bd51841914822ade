#pragma once
// Representations of the lighting-independent vision (B-Human 2021, section 5). Image
// coordinates follow docs/conventions.md (pixel centres at i + 0.5); "robot" means the robot
// frame on the ground. Every threshold behind these is computed from the image at hand.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "robot/CameraImage.h"

namespace nao {

// YHS2 colour (B-Human's "YHS2": luminance, hue, saturation from YUV), each 0..255:
// h = atan2(v - 128, u - 128) at 256 per turn, s = 2 * hypot(u - 128, v - 128) clamped
// (perception/vision/Yhs.h converts).
struct Yhs {
  std::uint8_t y = 0, h = 0, s = 0;
};

// Unknown after classification: sensor-saturated, no colour to go by (ScanLineRegionizer.h).
enum class RegionClass : std::uint8_t { Unknown, Field, White, Other };

// A run of similar pixels on one scan line.
struct ScanRegion {
  int from = 0, to = 0;  // [from, to) along the scan line (y for vertical lines, x for horizontal)
  Yhs colour;            // mean colour of the region
  std::uint8_t u = 128, v = 128;
  RegionClass cls = RegionClass::Unknown;
};

struct ScanLine {
  int coord = 0;             // x of a vertical line, y of a horizontal line (pixel index)
  int start = 0, end = 0;    // scanned range [start, end) along the line
  std::vector<ScanRegion> regions;
};

// The field colour of THIS image, found from its biggest united green regions.
struct FieldColour {
  bool valid = false;
  std::uint8_t hueMin = 0, hueMax = 0;  // hue range (YHS2)
  std::uint8_t satMin = 0;              // minimum saturation
  std::uint8_t yMin = 0, yMax = 255;    // luminance range
  double meanY = 0, meanS = 0;          // image averages the white thresholds are relative to
  // Added by the regionizer (perception/vision/ScanLineRegionizer.h): the field's own mean
  // colour (medians), this image's white point (the chroma per luminance, (u - 128) / y and
  // (v - 128) / y, of the white things on the field: about 0 with white balance, orange in
  // warm light without), the white thresholds it classified with (white: y >= whiteYMin and
  // the chroma about the white point, |(u - 128 - y whiteU, v - 128 - y whiteV)|, <=
  // whiteChromaPerY * y; whiteSMax is that bound at whiteYMin in YHS2 units; or clearly
  // brighter and greyer than the field regions beside it) and the smoothed-luminance step
  // between two samples that splits a region.
  std::uint8_t fieldY = 0, fieldHue = 0, fieldS = 0;
  double whiteU = 0, whiteV = 0;
  std::uint8_t whiteYMin = 255, whiteSMax = 0;
  double whiteChromaPerY = 0;
  double edgeThreshold = 0;
};

// Where the field ends in the image: the boundary's image y as a polyline over x.
struct FieldBoundary {
  bool valid = false;
  std::vector<Eigen::Vector2d> points;  // sorted by x, image pixels
  // The boundary's y at column x (interpolated; the image top when invalid).
  double yAt(double x) const;
};

// Image regions of other robots; line spots and ball candidates inside them are ignored.
struct ObstaclesPercept {
  struct Obstacle {
    int left = 0, right = 0, top = 0, bottom = 0;  // image box
    Eigen::Vector2d footRobot = Eigen::Vector2d::Zero();
  };
  std::vector<Obstacle> obstacles;
  bool contains(double x, double y) const;
};

struct ScanLineRegions {
  CameraId camera = CameraId::Top;
  std::vector<ScanLine> vertical, horizontal;
  FieldColour fieldColour;
  int saturationLevel = -1;  // luminance at which this image's sensor clips, if it does over wide areas
};

struct LinesPercept {
  struct Line {
    Eigen::Vector2d imageFrom, imageTo;  // pixels
    Eigen::Vector2d from, to;            // robot frame, m (the line's centre)
    std::vector<Eigen::Vector2d> spots;  // the line spots it was fitted to (image)
  };
  struct Intersection {
    enum class Type { L, T, X } type = Type::L;
    Eigen::Vector2d position = Eigen::Vector2d::Zero();  // robot frame
    Eigen::Vector2d image = Eigen::Vector2d::Zero();
    int line1 = -1, line2 = -1;
  };
  struct Circle {
    bool found = false;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // robot frame
    double radius = 0;
  };
  // The goal box seen from the side: a short line joining two long lines, found in the image
  // without the (possibly wrong) projection. Indices into `lines`.
  struct GoalBoxSide {
    bool found = false;
    int shortLine = -1, longLine1 = -1, longLine2 = -1;
  };
  std::vector<Line> lines;
  std::vector<Intersection> intersections;
  Circle circle;
  std::optional<Eigen::Vector2d> penaltyMark;  // robot frame
  GoalBoxSide goalBoxSide;
};

struct BallPercept {
  bool seen = false;
  Eigen::Vector2d image = Eigen::Vector2d::Zero();     // centre, pixels
  double radiusPx = 0;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // robot frame, m
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();
  double confidence = 0;
};

}  // namespace nao
