#pragma once
// Everything one camera image showed (CameraPerceptsProvider, the last module of the camera
// pipeline, perception/vision/CameraPipeline.h): which camera, when the image was exposed,
// the camera matrix at that time, and the percepts in the robot frame at that time.
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "perception/CameraModel.h"
#include "perception/vision/VisionTypes.h"
#include "robot/CameraImage.h"

namespace nao {

struct CameraPercepts {
  CameraId camera = CameraId::Top;
  double timestamp = 0;  // s, backend clock: the image's exposure
  CameraMatrix cameraMatrix;  // at exposure time, calibrated
  bool processed = false;     // the vision ran on the image (false: no camera matrix yet, or no pixels)

  std::vector<LinesPercept::Line> lines;
  std::vector<LinesPercept::Intersection> intersections;  // line1/line2 index `lines`
  LinesPercept::Circle circle;
  std::optional<Eigen::Vector2d> penaltyMark;  // robot frame
  Eigen::Vector2d penaltyMarkImage = Eigen::Vector2d::Zero();
  LinesPercept::GoalBoxSide goalBoxSide;  // indices into `lines`
  BallPercept ball;
  ObstaclesPercept obstacles;
  FieldBoundary fieldBoundary;

  // The line features together, as the older LinesPercept.
  LinesPercept linesPercept() const {
    LinesPercept p;
    p.lines = lines;
    p.intersections = intersections;
    p.circle = circle;
    p.penaltyMark = penaltyMark;
    p.goalBoxSide = goalBoxSide;
    return p;
  }
};

}  // namespace nao
