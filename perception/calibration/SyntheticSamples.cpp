#include "perception/calibration/SyntheticSamples.h"

namespace nao::calibration {

std::optional<CalibrationSample> synthesizeSample(const SyntheticScene& scene, const JointArray& joints,
                                                  CameraId camera, const CameraCalibration& truth,
                                                  const CameraIntrinsics& intrinsics) {
  const CameraMatrix cm = computeCameraMatrix(joints, scene.imuAngle, camera, truth, intrinsics);
  const GoalBoxSide& s = scene.side;
  const double hw = scene.lineWidth / 2;
  const Eigen::Vector2d along = (s.lCorner - s.tJunction).normalized();
  const Eigen::Vector2d acrossShort(-along.y(), along.x());
  auto turned = [](const Eigen::Vector2d& d, double a) {
    return Eigen::Vector2d(std::cos(a) * d.x() - std::sin(a) * d.y(), std::sin(a) * d.x() + std::cos(a) * d.y());
  };
  const Eigen::Vector2d inward1 = turned(s.inward, scene.longLine1Turn), inward2 = turned(s.inward, scene.longLine2Turn);
  const Eigen::Vector2d across1(-inward1.y(), inward1.x()), across2(-inward2.y(), inward2.x());
  const double shortLength = (s.lCorner - s.tJunction).norm();

  CalibrationSample sample;
  sample.camera = camera;
  sample.intrinsics = intrinsics;
  sample.joints = joints;
  sample.imuAngle = scene.imuAngle;
  // A line's two paint edges between centre points a and b, offset by half the width.
  auto measure = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& across,
                     LineMeasurement& out) {
    ImageLine* edges[2] = {&out.edgeA, &out.edgeB};
    for (int e = 0; e < 2; ++e) {
      const double sign = e == 0 ? 1 : -1;
      const auto pa = cm.fieldToImage(Eigen::Vector2d(a + sign * hw * across), scene.robotPose);
      const auto pb = cm.fieldToImage(Eigen::Vector2d(b + sign * hw * across), scene.robotPose);
      if (!pa || !pb) return false;
      *edges[e] = {*pa, *pb};
    }
    out.support = 100;
    return true;
  };
  const double margin = 2 * scene.lineWidth;
  if (!measure(s.tJunction + margin * along, s.tJunction + (shortLength - margin) * along, acrossShort,
               sample.lines[ShortLine]) ||
      !measure(s.tJunction + margin * inward1, s.tJunction + scene.longLength * inward1, across1,
               sample.lines[LongLine1]) ||
      !measure(s.lCorner + margin * inward2, s.lCorner + scene.longLength * inward2, across2,
               sample.lines[LongLine2]))
    return std::nullopt;
  return sample;
}

}  // namespace nao::calibration
