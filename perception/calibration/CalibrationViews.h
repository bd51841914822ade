#pragma once
// Where the robot looks during the calibration. It stands at the side of its own goal box,
// outside it, looking at the box's side line (the "short line") from the side, so that the
// goal line and the goal-box front line run away from it on either side (B-Human 2021, Fig. 1).
// Each camera takes the box at several head pan angles; the body turns the other way so that
// the box stays in view. Different pan angles are what separate the body offsets (they turn
// with the torso, not with the head) from the camera offsets (paper: "this is necessary to
// distribute the error among the body and camera offsets").
// Five pan angles per camera over +-45 deg (the paper: three), because, measured in the
// simulator over 30 random trials each: with three per camera, a single rejected view leaves a
// camera without enough samples (1 trial of 30 failed); with the pans within +-20 deg instead
// of +-45 the 95th-percentile errors triple (0.058 vs 0.02 deg): the wider the pans, the
// better body and camera offsets separate.
// The plan needs only roughly where the robot is: the pose it believes it has.
#include <vector>

#include <Eigen/Core>

#include "perception/FieldDimensions.h"
#include "robot/CameraImage.h"
#include "robot/JointIds.h"

namespace nao::calibration {

// One side of a goal box: the short line from the T junction on the goal line to the L
// corner on the goal-box front line; both long lines run from there in `inward`.
struct GoalBoxSide {
  Eigen::Vector2d tJunction = Eigen::Vector2d::Zero();  // goal line meets the short line
  Eigen::Vector2d lCorner = Eigen::Vector2d::Zero();    // front line meets the short line
  Eigen::Vector2d inward = Eigen::Vector2d::Zero();     // unit, along the long lines into the box
  Eigen::Vector2d middle() const { return (tJunction + lCorner) / 2; }
};

// The own goal box's side nearer to the side line at sideSign (-1: right, y < 0; +1: left).
GoalBoxSide ownGoalBoxSide(const FieldDimensions& field, int sideSign);

// The challenge's start: on the side line (sideSign), in line with the own penalty mark, facing
// into the field.
Eigen::Vector3d initialPosition(const FieldDimensions& field, int sideSign);

struct ViewPlanOptions {
  std::vector<double> topYawsDeg = {-45, -22.5, 0, 22.5, 45};     // head pan angles, top camera
  std::vector<double> bottomYawsDeg = {-45, -22.5, 0, 22.5, 45};  // bottom camera
  double distance = 1.0;          // m from the short line's middle, outside the box
  double targetRow = 0.55;        // where the short line's middle should appear (fraction of height)
  double minPitchDeg = -30;       // head pitch range used (inside the NAO's -38.5..29.5 at any yaw up to 45 deg)
  double maxPitchDeg = 25;
};

// The calibration position: `distance` in front of the box side's middle, facing it.
Eigen::Vector3d calibrationPosition(const GoalBoxSide& side, const ViewPlanOptions& options = {});

struct CalibrationView {
  CameraId camera = CameraId::Top;
  double headYaw = 0, headPitch = 0;                   // rad
  Eigen::Vector3d robotPose = Eigen::Vector3d::Zero();  // where the body should stand/face (field)
};

// The views for a robot that believes it stands at `position` (x, y; its heading is chosen
// per view): per camera and pan angle, the body heading that keeps the short line's middle
// at the pan angle, and the head pitch that puts it at targetRow in that camera (nominal
// camera model, the given standing posture).
std::vector<CalibrationView> planViews(const GoalBoxSide& side, const Eigen::Vector2d& position,
                                       const JointArray& standPosture, const ViewPlanOptions& options = {});

}  // namespace nao::calibration
