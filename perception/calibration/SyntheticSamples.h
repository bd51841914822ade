#pragma once
// Exact samples without images: the paint edges of a goal box side projected into the image
// with the true offsets and the true robot pose. For unit tests (the solvers must recover the
// truth from them) and for studying which views determine the offsets well.
#include <optional>

#include "perception/CameraCalibration.h"
#include "perception/calibration/CalibrationSample.h"
#include "perception/calibration/CalibrationViews.h"

namespace nao::calibration {

struct SyntheticScene {
  GoalBoxSide side;
  double lineWidth = 0.05;     // m
  double longLength = 0.8;     // m of each long line used, from the short line inwards
  // Paint off the true geometry: each long line turned about its junction (rad, counterclockwise).
  double longLine1Turn = 0, longLine2Turn = 0;
  Eigen::Vector3d robotPose = Eigen::Vector3d::Zero();  // true (x, y, theta)
  Eigen::Vector2d imuAngle = Eigen::Vector2d::Zero();   // true torso roll, pitch
};

// The sample that camera `camera` with the true offsets `truth` would give; nullopt when a
// line end is behind the camera.
std::optional<CalibrationSample> synthesizeSample(const SyntheticScene& scene, const JointArray& joints,
                                                  CameraId camera, const CameraCalibration& truth,
                                                  const CameraIntrinsics& intrinsics);

}  // namespace nao::calibration
