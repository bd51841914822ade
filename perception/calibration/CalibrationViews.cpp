#include "perception/calibration/CalibrationViews.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "perception/CameraModel.h"
#include "perception/Geometry.h"
#include "robot/Error.h"

namespace nao::calibration {
namespace {
constexpr double kDeg = std::numbers::pi / 180;
}

GoalBoxSide ownGoalBoxSide(const FieldDimensions& field, int sideSign) {
  if (!field.hasGoalBox) throw Error("field dimensions", "the calibration needs a goal box (field.goalBoxArea*)");
  if (sideSign != 1 && sideSign != -1) throw Error("calibration", "side must be +1 (left) or -1 (right)");
  const double goalX = -field.length / 2, y = sideSign * field.goalBoxAreaWidth / 2;
  GoalBoxSide s;
  s.tJunction = {goalX, y};
  s.lCorner = {goalX + field.goalBoxAreaLength, y};
  s.inward = {0, -static_cast<double>(sideSign)};
  return s;
}

Eigen::Vector3d initialPosition(const FieldDimensions& field, int sideSign) {
  if (sideSign != 1 && sideSign != -1) throw Error("calibration", "side must be +1 (left) or -1 (right)");
  return {-field.length / 2 + field.penaltyCrossDistance, sideSign * field.width / 2, -sideSign * std::numbers::pi / 2};
}

Eigen::Vector3d calibrationPosition(const GoalBoxSide& side, const ViewPlanOptions& options) {
  const Eigen::Vector2d p = side.middle() - options.distance * side.inward;
  return {p.x(), p.y(), std::atan2(side.inward.y(), side.inward.x())};
}

std::vector<CalibrationView> planViews(const GoalBoxSide& side, const Eigen::Vector2d& position,
                                       const JointArray& standPosture, const ViewPlanOptions& options) {
  std::vector<CalibrationView> views;
  const Eigen::Vector2d target = side.middle();
  const double bearing = std::atan2(target.y() - position.y(), target.x() - position.x());
  for (CameraId camera : {CameraId::Top, CameraId::Bottom}) {
    const CameraIntrinsics in = CameraIntrinsics::nominal(camera);
    for (double yawDeg : camera == CameraId::Top ? options.topYawsDeg : options.bottomYawsDeg) {
      CalibrationView v;
      v.camera = camera;
      v.headYaw = yawDeg * kDeg;
      v.robotPose = Eigen::Vector3d(position.x(), position.y(), normalizeAngle(bearing - v.headYaw));
      // The head pitch that puts the target at the wanted row: the row grows with the pitch
      // (looking down moves the ground up in the image), so bisect.
      JointArray joints = standPosture;
      joints[HeadYaw] = v.headYaw;
      auto rowAt = [&](double pitch) {
        joints[HeadPitch] = pitch;
        const CameraMatrix cm = computeCameraMatrix(joints, Eigen::Vector2d::Zero(), camera, CameraCalibration{}, in);
        const auto px = cm.fieldToImage(target, v.robotPose);
        return px ? px->y() : -1e9;
      };
      double lo = options.minPitchDeg * kDeg, hi = options.maxPitchDeg * kDeg;
      const double want = options.targetRow * in.height;
      for (int i = 0; i < 50; ++i) {
        const double mid = (lo + hi) / 2;
        // Looking further down raises the target in the image (smaller row).
        if (rowAt(mid) > want) lo = mid;
        else hi = mid;
      }
      v.headPitch = std::clamp((lo + hi) / 2, options.minPitchDeg * kDeg, options.maxPitchDeg * kDeg);
      views.push_back(v);
    }
  }
  return views;
}

}  // namespace nao::calibration
