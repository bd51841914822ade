#pragma once
// Head control: where the cameras look. The behaviour asks for fixed angles, a point to look at
// (robot- or field-relative, with the top or the bottom camera), a pan sweep, or one view of
// the camera calibration's pattern; HeadControl turns that into HeadYaw/HeadPitch targets that
// move no faster than the speed limits (and accelerate smoothly), so images stay sharp and the
// camera matrix stays valid. It reports when the head has arrived and held still long enough
// for an image taken then to show the requested view.
//
// The calibration pattern (calibrationPattern()): three pan angles per camera, in order,
// each held still while an image is taken:
//   for (std::size_t i = 0; i < HeadControl::calibrationPattern().size(); ++i) {
//     request.mode = HeadMotionRequest::Mode::Calibration; request.calibrationIndex = i;
//     ... run cycles until headControl.settled(), then use the next image of pattern[i].camera
//   }
#include <vector>

#include <Eigen/Geometry>

#include "representations/behavior/HeadMotionRequest.h"
#include "representations/motion/HeadJointRequest.h"
#include "robot/CameraImage.h"
#include "robot/SensorData.h"

namespace nao {

// One view of the calibration pattern.
struct CalibrationView {
  double yaw = 0, pitch = 0;  // rad
  CameraId camera = CameraId::Top;
};

class HeadControl {
 public:
  struct Params {
    double maxYawSpeed = 3.0;     // rad/s (the servo does ~8)
    double maxPitchSpeed = 2.0;   // rad/s
    double maxAcceleration = 20;  // rad/s^2
    double arrivedTolerance = 0.01;   // rad between the joint reading and the goal
    double stillSpeed = 0.05;     // rad/s: the joints are still below this ...
    double settleTime = 0.1;      // s ... for this long, then settled()
  };

  // Top camera at HeadPitch 0.1 rad, bottom camera at 0.0 rad, each at yaw -40, 0, +40 deg.
  static const std::vector<CalibrationView>& calibrationPattern();

  // HeadYaw/HeadPitch (rad, clamped to the joint and the shoulder-view limits) that aim the
  // camera's optical axis at a robot-frame point, given the torso pose in the robot frame.
  static Eigen::Vector2d anglesToLookAt(const Eigen::Vector3d& pointRobot, CameraId camera,
                                        const Eigen::Isometry3d& robotToTorso);

  HeadControl() = default;
  explicit HeadControl(const Params& params) : params_(params) {}

  HeadJointRequest update(const SensorFrame& frame, const HeadMotionRequest& request,
                          const Eigen::Isometry3d& robotToTorso = Eigen::Isometry3d::Identity());
  // The commanded angles are at the goal, the joints read it and have been still for settleTime.
  bool settled() const { return settled_; }
  Eigen::Vector2d goal() const { return goal_; }

 private:
  Params params_;
  bool initialized_ = false;
  double lastTime_ = 0;
  Eigen::Vector2d command_ = Eigen::Vector2d::Zero(), velocity_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d goal_ = Eigen::Vector2d::Zero(), lastReading_ = Eigen::Vector2d::Zero();
  double sweepPhase_ = 0;
  double stillSince_ = -1;
  bool settled_ = false;
};

}  // namespace nao
