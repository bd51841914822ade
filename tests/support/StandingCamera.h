#pragma once
// The camera matrix of a NAO standing at the origin with the given head angles (no offsets,
// nominal intrinsics): the camera the synthetic-image tests draw with.
#include <cmath>

#include "controllers/StandController.h"
#include "perception/CameraModel.h"

namespace nao::test {

inline CameraMatrix standingCamera(double yawDeg, double pitchDeg, CameraId camera = CameraId::Top) {
  constexpr double kDegree = M_PI / 180;
  JointArray joints = StandController::standPosture();
  joints[HeadYaw] = yawDeg * kDegree;
  joints[HeadPitch] = pitchDeg * kDegree;
  return computeCameraMatrix(joints, Eigen::Vector2d::Zero(), camera, CameraCalibration{},
                             CameraIntrinsics::nominal(camera));
}

}  // namespace nao::test
