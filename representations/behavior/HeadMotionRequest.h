#pragma once
// Where the behaviour wants the cameras to look (HeadControl turns it into HeadJointRequest).
// Until a behaviour module provides it, a pipeline input that scenarios and tests write.
#include <cstddef>

#include <Eigen/Core>

#include "robot/CameraImage.h"

namespace nao {

struct HeadMotionRequest {
  enum class Mode { Angles, LookAtRobotPoint, LookAtFieldPoint, Sweep, Calibration };
  Mode mode = Mode::Angles;
  double yaw = 0, pitch = 0;                      // Angles (rad)
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // LookAt*: m, robot or field frame
  Eigen::Vector3d robotPose = Eigen::Vector3d::Zero();  // LookAtFieldPoint: the robot's field pose (x, y, theta)
  CameraId camera = CameraId::Top;                // LookAt*: the camera whose centre aims at the point
  double sweepAmplitude = 1.0;                    // Sweep: yaw goes +-amplitude (rad) ...
  double sweepPitch = 0.2;                        // ... at this pitch
  double sweepSpeed = 1.0;                        // rad/s along the sweep
  std::size_t calibrationIndex = 0;               // Calibration: the view in HeadControl::calibrationPattern()
  double maxSpeed = 0;                            // rad/s; 0 = the default limit
};

}  // namespace nao
