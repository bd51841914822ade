#pragma once
// A camera matrix as a robot recorded it beside an image, and the image's line labels: the
// labelled-frame JSON of ../shared/data/real-goalbox-images/README.md (the HULKs' format).
// Its frames match ours once the ground frame is taken as our robot frame: camera_to_ground
// has x forward, y left, z up at the floor, and the camera's x is the optical axis, y image
// left, z image up (checked on all 39 frames: the labelled goal-box lines meet at 81-90 deg
// on the ground, parallels within 3.2 deg). The intrinsics are those of a 640x480 image.
#include <string>
#include <vector>

#include "perception/CameraModel.h"
#include "perception/FieldDimensions.h"

namespace nao {

// Two image points (px) on one painted line.
struct LabelledLine {
  std::string name;  // "border_line", "goal_box_line", "connecting_line"
  Eigen::Vector2d a = Eigen::Vector2d::Zero(), b = Eigen::Vector2d::Zero();
};

struct RecordedCameraMatrix {
  CameraId camera = CameraId::Top;  // "position"
  CameraMatrix matrix;              // pose = camera_to_ground; intrinsics for 640x480
  std::vector<LabelledLine> lines;  // from "crossings"; empty when the file has none

  // The matrix for an image of width x height (the intrinsics scaled from 640x480).
  CameraMatrix forImage(int width, int height) const;
  // The labelled line of that name, or nullptr.
  const LabelledLine* line(const std::string& name) const;

  // Where the robot stood on `field` (x, y, theta of its ground frame) for its labelled goal-box
  // lines to be the own goal's box: the goal line meets the side line at the goal box's corner
  // on the goal line, the side line runs along the field's x axis. The side (left or right goal
  // box corner) follows from which way the goal-box front line runs on from the side line.
  // Throws nao::Error(source, "crossings: ...") when a line is missing or does not reach the
  // ground. For render --camera-matrix: the simulator's twin of the real image.
  Eigen::Vector3d robotPoseOnField(const FieldDimensions& field, const std::string& source) const;

  // Throws nao::Error(source, "field.path: problem") for invalid JSON, a missing key, a value of
  // the wrong type or not finite, a rotation that is not a unit quaternion (|q| off 1 by more
  // than 1e-3), a camera below 0.05 m or above 1 m, a focal length outside 100..5000 px, an
  // optical centre off the image.
  static RecordedCameraMatrix parse(const std::string& text, const std::string& source);
  static RecordedCameraMatrix read(const std::string& path);

  static constexpr int kWidth = 640, kHeight = 480;  // the size the file's intrinsics are for
};

}  // namespace nao
