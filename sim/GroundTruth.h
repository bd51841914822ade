#pragma once
// What a robot's camera truly sees, from the simulator's state alone (true camera pose,
// field model, ball positions, occlusion by ray casting). For scenarios, evaluations and
// tests only: the robot program never reads it.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "perception/FieldDimensions.h"
#include "robot/CameraImage.h"

namespace nao::sim {

class World;

struct VisibleLine {
  int index = -1;                     // into FieldModel::lines
  std::string name;
  Eigen::Vector2d from, to;           // the visible stretch of the line's centre, field frame
  Eigen::Vector2d imageFrom, imageTo; // its pixels
  double visibleLength = 0;           // m
};

struct VisibleIntersection {
  FieldIntersection intersection;
  Eigen::Vector2d image;
};

struct VisibleBall {
  int index = -1;
  Eigen::Vector3d position;  // field frame
  Eigen::Vector2d image;     // centre pixel
  double radiusPx = 0;
  double distance = 0;       // m, from the camera's ground point
};

struct VisibleFeatures {
  std::vector<VisibleLine> lines;
  std::vector<VisibleIntersection> intersections;
  double centreCircleFractionVisible = 0;  // of the circle's length, 0..1
  std::optional<Eigen::Vector2d> penaltyCross;
  std::vector<VisibleBall> balls;
};

// The true pixel of a field point seen by robot's camera (nullopt behind the camera).
std::optional<Eigen::Vector2d> truePixel(const World& world, int robot, CameraId camera, const Eigen::Vector3d& pField);

// Whether a field point is in the image and not hidden behind anything (goals, robots, the
// robot's own body). Points farther than maxDistance (m, on the ground) do not count.
bool trulyVisible(const World& world, int robot, CameraId camera, const Eigen::Vector3d& pField,
                  double maxDistance = 1e9);

// The first visible geom (mj_ray's: not transparent) on the segment from..to: its fraction of
// the way (0..1) and its id, as mj_ray finds it, but trying only the geoms near the segment.
struct SegmentHit {
  double fraction = 0;
  int geom = -1;
};
std::optional<SegmentHit> firstHit(const World& world, const Eigen::Vector3d& from, const Eigen::Vector3d& to);

// The share (0..1) of a ball's image disc (centre, radius in pixels) inside a width x height image.
double discInImage(const Eigen::Vector2d& centre, double radiusPx, int width, int height);

// Whether ball `ball` is in the image and unhidden: its centre or its point nearest the camera.
bool ballVisible(const World& world, int robot, CameraId camera, int ball, double maxDistance = 1e9);

// The visible stretch of field line `index`: the longest run of its centre's 2 cm samples
// that are truly visible. With wholePaintWidth a sample also needs both edges of the paint
// across the line inside the image: where the border cuts the paint lengthwise, what is left
// is a sliver whose centre no image shows.
std::optional<VisibleLine> visibleStretch(const World& world, int robot, CameraId camera, int index,
                                          double maxDistance, bool wholePaintWidth = false);

// Everything in view of robot's camera within maxDistance. Lines are sampled every 2 cm;
// a line's visible stretch is the longest run of visible samples.
VisibleFeatures visibleFeatures(const World& world, int robot, CameraId camera, double maxDistance = 1e9);

}  // namespace nao::sim
