#pragma once
// Forward kinematics of the NAO V6 (docs/conventions.md, robot/RobotDimensions.h).
// Every pose maps coordinates of the child frame into the parent frame (T_parent_child);
// the root is the torso frame (origin midway between the hip joints, x forward, z up).
#include <Eigen/Geometry>

#include "robot/CameraImage.h"
#include "robot/JointIds.h"
#include "robot/SensorData.h"

namespace nao {

enum class BodySide { Left, Right };

// Rotations about the frame axes (rad).
Eigen::Matrix3d rotX(double a);
Eigen::Matrix3d rotY(double a);
Eigen::Matrix3d rotZ(double a);

// The HeadPitch joint frame ("head"): Trans(0, 0, 0.2115) Rz(HeadYaw) Ry(HeadPitch).
Eigen::Isometry3d torsoToHead(const JointArray& joints);
// A camera's nominal mount in the head frame, B-Human camera axes (x optical axis,
// y image left, z image up): Trans(mount) Ry(mount pitch).
Eigen::Isometry3d headToCamera(CameraId camera);
// torsoToHead * headToCamera, without any calibration offset.
Eigen::Isometry3d torsoToCamera(const JointArray& joints, CameraId camera);

// The sole frame: the point kFootHeight below the ankle, with the foot's axes (after
// AnkleRoll). The right HipYawPitch uses the LHipYawPitch angle (one motor).
Eigen::Isometry3d torsoToSole(const JointArray& joints, BodySide side);
// The ankle (AnklePitch/AnkleRoll) frame.
Eigen::Isometry3d torsoToAnkle(const JointArray& joints, BodySide side);
// The hand frame: after WristYaw, translated by the hand offset.
Eigen::Isometry3d torsoToHand(const JointArray& joints, BodySide side);

// The yaw-free torso orientation of the robot frame: Ry(pitch) Rx(roll) (IMU angles).
Eigen::Matrix3d torsoTilt(double roll, double pitch);

// How the torso height is measured from a foot.
enum class SoleContact {
  LowestCorner,  // the lowest corner of the sole rectangle (what a tilted rigid sole rests on)
  Centre,        // the sole centre below the ankle (insensitive to small foot tilts)
};

// Height of the torso origin above the ground, taken from the lower of the two feet (the
// support foot) with the torso oriented Ry(pitch) Rx(roll). Default: the lowest corner of
// either sole rectangle touches the ground; with flat feet both choices agree.
double torsoHeightAboveGround(const JointArray& joints, double roll, double pitch,
                              SoleContact contact = SoleContact::LowestCorner);

// T_robot_torso: Trans(0, 0, torsoHeightAboveGround) * torsoTilt(roll, pitch).
Eigen::Isometry3d robotToTorso(const JointArray& joints, double roll, double pitch,
                               SoleContact contact = SoleContact::LowestCorner);
// The same from one sensor frame's joint angles and IMU roll and pitch.
inline Eigen::Isometry3d robotToTorso(const SensorFrame& sensors) {
  return robotToTorso(sensors.joints.position, sensors.inertial.angle.x(), sensors.inertial.angle.y());
}

}  // namespace nao
