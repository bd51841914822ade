#pragma once
// Where the robot is on the field (SelfLocalization provides it): field frame, SPL
// conventions (origin at the centre, x towards the opponent goal, y left).
#include <Eigen/Core>

#include "robot/math/Pose2.h"

namespace nao {

// The self-localization's result.
struct RobotPose {
  Pose2 pose;                                                // the robot in the field frame
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();  // of (x m, y m, theta rad)
  double quality = 0;  // 0..1: the best hypothesis' recent share of percepts that fitted
  bool valid = false;  // quality and covariance good enough to act on
  int hypotheses = 0;  // how many hypotheses the filter keeps
  double time = -1;    // s, backend clock: the exposure of the image it was last updated with
  Pose2 odometry;      // the odometry pose at that time: field = pose * odometry^-1 * odometry-frame pose
  double sigmaTranslation() const;  // m, sqrt of the largest eigenvalue of the xy block
  double sigmaRotation() const;     // rad
};

}  // namespace nao
