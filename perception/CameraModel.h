#pragma once
// The camera model: intrinsics from the field of view, the camera pose in the robot frame
// from the joint angles, the IMU and the calibration offsets, and pixel <-> robot/field
// mappings (docs/conventions.md). Everything is fixed-size Eigen: no allocations, cheap
// enough to project thousands of points per frame.
#include <cmath>
#include <optional>

#include <Eigen/Geometry>

#include "perception/CameraCalibration.h"
#include "robot/CameraImage.h"
#include "robot/ForwardKinematics.h"
#include "robot/JointIds.h"
#include "robot/RobotDimensions.h"

namespace nao {

// Pinhole intrinsics (pixels). Square pixels, principal point at (W/2, H/2); pixel (i, j)
// covers [i, i+1) x [j, j+1), so its centre is (i + 0.5, j + 0.5).
struct CameraIntrinsics {
  int width = dims::kTopWidth, height = dims::kTopHeight;
  double fx = (dims::kTopHeight / 2.0) / std::tan(dims::kCameraFovY / 2);
  double fy = fx;
  double cx = dims::kTopWidth / 2.0, cy = dims::kTopHeight / 2.0;

  // f = (H/2) / tan(fovY/2) for both axes. Throws nao::Error on a non-positive size or a
  // field of view outside (0, pi).
  static CameraIntrinsics fromFovY(int width, int height, double fovY = dims::kCameraFovY);
  // The default resolution of a camera (top 640x480, bottom 320x240) with the NAO's fovY.
  static CameraIntrinsics nominal(CameraId camera);
  double fovX() const { return 2 * std::atan(width / (2 * fx)); }
  double fovY() const { return 2 * std::atan(height / (2 * fy)); }
};

// A line segment in the image (pixels).
struct ImageLine {
  Eigen::Vector2d from, to;
};

// A camera's pose in the robot frame (T_robot_camera, B-Human camera axes: x optical axis,
// y image left, z image up) and its intrinsics.
struct CameraMatrix {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  CameraIntrinsics intrinsics;

  // A robot-frame point in camera coordinates.
  Eigen::Vector3d robotToCamera(const Eigen::Vector3d& pRobot) const {
    return pose.linear().transpose() * (pRobot - pose.translation());
  }
  // The pixel of a robot-frame point; nullopt if it is not in front of the camera (it may
  // still be off the image: see isOnImage).
  std::optional<Eigen::Vector2d> project(const Eigen::Vector3d& pRobot) const {
    const Eigen::Vector3d p = robotToCamera(pRobot);
    if (p.x() <= kMinDepth) return std::nullopt;
    return Eigen::Vector2d(intrinsics.cx - intrinsics.fx * p.y() / p.x(),
                           intrinsics.cy - intrinsics.fy * p.z() / p.x());
  }
  // The pixel of a robot-frame ground point (z = 0).
  std::optional<Eigen::Vector2d> projectGround(const Eigen::Vector2d& pRobot) const {
    return project(Eigen::Vector3d(pRobot.x(), pRobot.y(), 0));
  }
  // The viewing ray of a pixel in the robot frame (not normalised; its camera-frame x is 1).
  Eigen::Vector3d pixelRay(const Eigen::Vector2d& pixel) const {
    return pose.linear() * Eigen::Vector3d(1, (intrinsics.cx - pixel.x()) / intrinsics.fx,
                                           (intrinsics.cy - pixel.y()) / intrinsics.fy);
  }
  // Where a pixel's ray meets the plane at height z (robot frame, x and y); nullopt when the
  // ray does not reach it in front of the camera (for z below the camera: at or above the horizon).
  std::optional<Eigen::Vector2d> pixelToGround(const Eigen::Vector2d& pixel, double z = 0) const {
    const Eigen::Vector3d ray = pixelRay(pixel);
    const double dz = z - pose.translation().z();
    if (std::abs(ray.z()) < 1e-12) return std::nullopt;
    const double t = dz / ray.z();
    if (!(t > 0)) return std::nullopt;
    return Eigen::Vector2d(pose.translation().x() + t * ray.x(), pose.translation().y() + t * ray.y());
  }
  bool isOnImage(const Eigen::Vector2d& pixel) const {
    return pixel.x() >= 0 && pixel.y() >= 0 && pixel.x() < intrinsics.width && pixel.y() < intrinsics.height;
  }
  // True if the pixel's ray points level or upwards (it never meets the ground).
  bool isAboveHorizon(const Eigen::Vector2d& pixel) const { return pixelRay(pixel).z() >= 0; }
  // The image row of the horizon at column x; nullopt when the horizon is vertical in the
  // image (camera rolled by 90 deg) or does not exist (camera looking straight up or down).
  std::optional<double> horizonY(double x) const;
  // The horizon as a segment spanning the image's width (from x = 0 to x = W; the ends may
  // lie above or below the image), or its height when it is closer to vertical; nullopt if
  // there is none.
  std::optional<ImageLine> horizon() const;

  // T_field_camera for a robot at robotPose = (x, y, theta).
  Eigen::Isometry3d fieldPose(const Eigen::Vector3d& robotPose) const;
  // The pixel of a field-frame point (3-D or on the ground) seen by a robot at robotPose.
  std::optional<Eigen::Vector2d> fieldToImage(const Eigen::Vector3d& pField, const Eigen::Vector3d& robotPose) const;
  std::optional<Eigen::Vector2d> fieldToImage(const Eigen::Vector2d& pField, const Eigen::Vector3d& robotPose) const {
    return fieldToImage(Eigen::Vector3d(pField.x(), pField.y(), 0), robotPose);
  }
  // The field-frame point (x, y) at height z that a pixel sees from a robot at robotPose.
  std::optional<Eigen::Vector2d> imageToField(const Eigen::Vector2d& pixel, const Eigen::Vector3d& robotPose,
                                              double z = 0) const;

  static constexpr double kMinDepth = 1e-6;  // m in front of the optical centre
};

// C_body * T_torso_head(joints) * T_head_cam_nominal * C_cam: the calibrated camera pose in
// the torso frame, with C_body = Rx(body_roll) Ry(body_pitch) and C_cam = Rx(roll) Ry(pitch)
// (the camera's offsets; camera frame, x = optical axis).
// The torso as the calibration believes it tilted: Rx(bodyRoll) Ry(bodyPitch), applied after
// robotToTorso (the camera matrix, the own body and its metering all use it).
Eigen::Isometry3d bodyOffset(const CameraCalibration& calib);
Eigen::Isometry3d torsoToCalibratedCamera(const JointArray& joints, CameraId camera, const CameraCalibration& calib);

// The camera matrix of a standing/walking robot: the torso is oriented Ry(pitch) Rx(roll)
// from the IMU (imuAngle = (roll, pitch)) and raised by the leg kinematics
// (torsoHeightAboveGround, lowest sole corner), then
// T_robot_cam = T_robot_torso * C_body * T_torso_head(joints) * T_head_cam * C_cam.
CameraMatrix computeCameraMatrix(const JointArray& joints, const Eigen::Vector2d& imuAngle, CameraId camera,
                                 const CameraCalibration& calib, const CameraIntrinsics& intrinsics);
// The same with a given torso pose in the robot frame (T_robot_torso) instead of IMU + legs.
CameraMatrix computeCameraMatrix(const JointArray& joints, const Eigen::Isometry3d& robotToTorso, CameraId camera,
                                 const CameraCalibration& calib, const CameraIntrinsics& intrinsics);

}  // namespace nao
