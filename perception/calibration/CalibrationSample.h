#pragma once
// One calibration sample (B-Human 2021, section 3): the goal box seen from the side in one
// camera image -- its short side line and the two long lines it joins (goal line and goal-box
// front line) -- plus what the robot knew at capture time: joint angles and torso roll/pitch.
// Each painted line is kept as its two paint edges, refined to sub-pixel precision in the
// image. The cost projects both edges to the ground and takes their bisector there, which is
// the line's centre exactly (the image midline of the two edges is not: perspective).
//
// What is calibrated, and why only that: the six offsets of perception/CameraCalibration.h
// (roll and pitch of the body and of each camera). The yaw offsets are left out because the
// goal box seen from an unknown robot pose has no absolute heading in it (a yaw offset looks
// like the robot standing turned); translations are left out because millimetre mount errors
// move a projected point far less than 0.1 deg of rotation does.
#include <array>
#include <optional>
#include <string>

#include <Eigen/Geometry>

#include "perception/CameraModel.h"
#include "robot/CameraImage.h"
#include "robot/JointIds.h"

namespace nao::calibration {

// The three lines of the goal box seen from the side, in this order.
enum LineRole : int { ShortLine = 0, LongLine1 = 1, LongLine2 = 2 };
inline constexpr std::array<const char*, 3> kLineRoleNames = {"short", "long1", "long2"};

// One painted line measured in the image: its two paint edges (sub-pixel, image pixels). The
// segment ends span the stretch the edge was measured on.
struct LineMeasurement {
  ImageLine edgeA, edgeB;
  int support = 0;     // edge points behind both fits
  double rmsPx = 0;    // of the edge points about their fitted lines
  // The image midline of the two edges (for drawing; the cost uses the edges).
  ImageLine centre() const;
};

struct CalibrationSample {
  CameraId camera = CameraId::Top;
  CameraIntrinsics intrinsics;
  JointArray joints{};                                  // rad, at capture time
  Eigen::Vector2d imuAngle = Eigen::Vector2d::Zero();   // torso roll, pitch at capture time
  std::array<LineMeasurement, 3> lines;                 // indexed by LineRole
  // A recorded real image has the robot's own camera matrix of the time instead of joint
  // angles: its camera pose in the robot frame (on the ground). With it the camera offsets
  // rotate that pose (camera frame, as computeCameraMatrix does) and the body offsets are
  // left out (the torso is not known): enough to check and measure a recorded sample.
  std::optional<Eigen::Isometry3d> cameraPose;
  double headYaw() const { return joints[HeadYaw]; }
};

// A sample the extraction refused, and why (shown to people: one line).
struct RejectedSample {
  CameraId camera = CameraId::Top;
  double headYaw = 0;  // rad
  std::string reason;
};

}  // namespace nao::calibration
