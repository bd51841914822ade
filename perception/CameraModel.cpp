#include "perception/CameraModel.h"

#include <numbers>
#include <string>

#include "perception/Geometry.h"
#include "robot/Error.h"

namespace nao {

CameraIntrinsics CameraIntrinsics::fromFovY(int width, int height, double fovY) {
  if (width <= 0 || height <= 0)
    throw Error("camera intrinsics", "image size must be positive (got " + std::to_string(width) + "x" +
                                         std::to_string(height) + ")");
  if (!(fovY > 0 && fovY < std::numbers::pi)) throw Error("camera intrinsics", "fovY must be in (0, 180) deg");
  CameraIntrinsics c;
  c.width = width;
  c.height = height;
  c.fy = (height / 2.0) / std::tan(fovY / 2);
  c.fx = c.fy;
  c.cx = width / 2.0;
  c.cy = height / 2.0;
  return c;
}

CameraIntrinsics CameraIntrinsics::nominal(CameraId camera) {
  return camera == CameraId::Top ? fromFovY(dims::kTopWidth, dims::kTopHeight)
                                 : fromFovY(dims::kBottomWidth, dims::kBottomHeight);
}

// The ray of pixel (u, v) has robot-frame z = A u + B v + C (with r = the robot z axis in
// camera coordinates); the horizon is where that vanishes.
namespace {
struct HorizonCoefficients {
  double a, b, c;
};
HorizonCoefficients horizonCoefficients(const CameraMatrix& m) {
  const auto r = m.pose.linear().row(2);
  const CameraIntrinsics& k = m.intrinsics;
  return {-r(1) / k.fx, -r(2) / k.fy, r(0) + r(1) * k.cx / k.fx + r(2) * k.cy / k.fy};
}
constexpr double kDegenerate = 1e-12;
}  // namespace

std::optional<double> CameraMatrix::horizonY(double x) const {
  const auto h = horizonCoefficients(*this);
  if (std::abs(h.b) < kDegenerate) return std::nullopt;
  return -(h.a * x + h.c) / h.b;
}

std::optional<ImageLine> CameraMatrix::horizon() const {
  const auto h = horizonCoefficients(*this);
  if (std::abs(h.a) < kDegenerate && std::abs(h.b) < kDegenerate) return std::nullopt;
  const double w = intrinsics.width, hh = intrinsics.height;
  if (std::abs(h.b) >= std::abs(h.a))
    return ImageLine{{0.0, -h.c / h.b}, {w, -(h.a * w + h.c) / h.b}};
  return ImageLine{{-h.c / h.a, 0.0}, {-(h.b * hh + h.c) / h.a, hh}};
}

Eigen::Isometry3d CameraMatrix::fieldPose(const Eigen::Vector3d& robotPose) const {
  return robotPoseToIsometry(robotPose) * pose;
}

std::optional<Eigen::Vector2d> CameraMatrix::fieldToImage(const Eigen::Vector3d& pField,
                                                          const Eigen::Vector3d& robotPose) const {
  const Eigen::Vector2d xy = fieldToRobot(pField.head<2>(), robotPose);
  return project(Eigen::Vector3d(xy.x(), xy.y(), pField.z()));
}

std::optional<Eigen::Vector2d> CameraMatrix::imageToField(const Eigen::Vector2d& pixel,
                                                          const Eigen::Vector3d& robotPose, double z) const {
  const auto p = pixelToGround(pixel, z);
  if (!p) return std::nullopt;
  return robotToField(*p, robotPose);
}

Eigen::Isometry3d bodyOffset(const CameraCalibration& calib) {
  Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();
  offset.linear() = rotX(calib.bodyRoll) * rotY(calib.bodyPitch);
  return offset;
}

Eigen::Isometry3d torsoToCalibratedCamera(const JointArray& joints, CameraId camera, const CameraCalibration& calib) {
  const bool top = camera == CameraId::Top;
  Eigen::Isometry3d cameraOffset = Eigen::Isometry3d::Identity();
  cameraOffset.linear() = top ? rotX(calib.topRoll) * rotY(calib.topPitch)
                              : rotX(calib.bottomRoll) * rotY(calib.bottomPitch);
  return bodyOffset(calib) * torsoToHead(joints) * headToCamera(camera) * cameraOffset;
}

CameraMatrix computeCameraMatrix(const JointArray& joints, const Eigen::Isometry3d& robotToTorsoPose,
                                 CameraId camera, const CameraCalibration& calib,
                                 const CameraIntrinsics& intrinsics) {
  CameraMatrix m;
  m.pose = robotToTorsoPose * torsoToCalibratedCamera(joints, camera, calib);
  m.intrinsics = intrinsics;
  return m;
}

CameraMatrix computeCameraMatrix(const JointArray& joints, const Eigen::Vector2d& imuAngle, CameraId camera,
                                 const CameraCalibration& calib, const CameraIntrinsics& intrinsics) {
  return computeCameraMatrix(joints, robotToTorso(joints, imuAngle.x(), imuAngle.y()), camera, calib, intrinsics);
}

}  // namespace nao
