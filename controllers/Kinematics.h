#pragma once
// NAO V6 inverse kinematics (legs with the shared HipYawPitch motor, arms) and the mass model
// (centre of mass from the joint angles). Forward kinematics is robot/ForwardKinematics.h; the
// frames are docs/conventions.md's (torso origin = hip midpoint), lengths robot/RobotDimensions.h.
//
// Legs. A leg alone has six joints and reaches any sole pose in its workspace: the knee follows
// from the hip-ankle distance, the ankle roll/pitch from that distance vector seen from the
// foot, and HipYawPitch/HipRoll/HipPitch from the remaining hip rotation, which in a frame
// turned 45 deg about x is a Y-X-Y Euler sequence. The NAO's two HipYawPitch joints are one
// motor, so both legs must use one angle: legsIK() blends the two free solutions' angles and
// solves each leg again with that angle fixed. The five remaining joints of a leg then reach
// the sole position and keep the sole flat in its own frame (its normal); only the sole's yaw
// about its normal is left to the shared joint. Walks that keep the torso's yaw midway between
// the feet need exactly the mirrored yaw both legs can give, so nothing is lost there.
//
// Arms. Given ElbowYaw and WristYaw, the hand point's distance from the shoulder fixes
// ElbowRoll, and ShoulderRoll/ShoulderPitch turn the arm onto the target direction.
#include <array>

#include <Eigen/Geometry>

#include "robot/ForwardKinematics.h"
#include "robot/JointIds.h"

namespace nao {

// The LoLA joints of one leg, hip to foot.
struct LegJoints {
  double hipYawPitch = 0, hipRoll = 0, hipPitch = 0, knee = 0, anklePitch = 0, ankleRoll = 0;
};

// The joint ids of a leg (LHipYawPitch for both: the right one does not exist in LoLA).
std::array<Joint, 6> legJointIds(BodySide side);
void setLeg(JointArray& joints, BodySide side, const LegJoints& leg);
LegJoints getLeg(const JointArray& joints, BodySide side);

// Joint limits (nao-v6.md), rad.
double jointMin(Joint joint);
double jointMax(Joint joint);
double clampToLimits(Joint joint, double angle);

// One leg, HipYawPitch free: the joints that put the sole frame (torsoToSole) at `target`.
// Returns false when the target is out of reach or beyond a joint limit; the joints are then
// the nearest the leg can do (the leg stretched towards the target, angles clamped).
bool legIK(const Eigen::Isometry3d& target, BodySide side, LegJoints& out);
// One leg with a given HipYawPitch angle: exact sole position and sole normal; the yaw about
// the normal is what the given angle leaves.
bool legIKFixedHipYawPitch(const Eigen::Isometry3d& target, BodySide side, double hipYawPitch, LegJoints& out);
// Both legs with the shared HipYawPitch: each leg's free angle, blended (ratio 1 = the left
// leg's, 0 = the right leg's), then both legs solved with that angle. Writes the leg joints
// of `joints` and returns whether both targets were reached.
bool legsIK(const Eigen::Isometry3d& left, const Eigen::Isometry3d& right, JointArray& joints, double ratio = 0.5);

// The joints of one arm.
struct ArmJoints {
  double shoulderPitch = 0, shoulderRoll = 0, elbowYaw = 0, elbowRoll = 0, wristYaw = 0;
};
void setArm(JointArray& joints, BodySide side, const ArmJoints& arm);
ArmJoints getArm(const JointArray& joints, BodySide side);
// The arm joints that put the hand point (torsoToHand) at `hand` (torso frame) with the given
// ElbowYaw and WristYaw. Returns false when out of reach; the arm then points at the target.
bool armIK(const Eigen::Vector3d& hand, BodySide side, double elbowYaw, double wristYaw, ArmJoints& out);

// The torques a leg's joints exert on their child links (N m, LegJoints order) to hold a force
// `force` (torso frame) applied to the foot at `point` (torso frame) in static equilibrium:
// tau_j = -a_j . ((point - o_j) x force) for joint axis a_j through o_j. A position servo with
// gain kp sags by tau / kp; adding that to the target compensates it.
std::array<double, 6> legJointTorques(const JointArray& joints, BodySide side, const Eigen::Vector3d& point,
                                      const Eigen::Vector3d& force);

// Whole-body IK for a centre-of-mass target: the torso (height torsoHeight, orientation
// Rz(yaw) Ry(pitch) in a ground frame) is shifted horizontally until the robot's COM lies above
// com (ground frame, x y), both soles at the given poses (ground frame). The arms and head keep
// the angles in `joints`; returns the torso pose found (ground frame) and writes the legs.
Eigen::Isometry3d comIK(const Eigen::Isometry3d& leftSole, const Eigen::Isometry3d& rightSole, const Eigen::Vector2d& com,
                        double torsoHeight, double torsoPitch, double torsoYaw, JointArray& joints,
                        const Eigen::Vector2d& torsoGuess = Eigen::Vector2d::Zero());

// Mass model (nao-v6.md's link masses and centres of mass).
double totalMass();
// The whole robot's centre of mass in the torso frame.
Eigen::Vector3d centerOfMass(const JointArray& joints);

}  // namespace nao
