// Forward kinematics of the NAO V6 against hand-computed poses (nao-v6.md, conventions.md).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <tuple>

#include "robot/ForwardKinematics.h"
#include "robot/RobotDimensions.h"

namespace nao {
namespace {

constexpr double kTol = 1e-9;
constexpr double kLeg = 0.1 + 0.1029 + 0.04519;  // 0.24809

void expectNear(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double tol = kTol) {
  EXPECT_NEAR((a - b).norm(), 0, tol) << "got " << a.transpose() << " expected " << b.transpose();
}

JointArray zeros() {
  JointArray j{};
  j.fill(0);
  return j;
}

TEST(Kinematics, LegLengthConstant) { EXPECT_NEAR(dims::kLegLength, 0.24809, 1e-12); }

TEST(Kinematics, ZeroPoseSoles) {
  const JointArray j = zeros();
  const auto l = torsoToSole(j, BodySide::Left);
  const auto r = torsoToSole(j, BodySide::Right);
  expectNear(l.translation(), {0, 0.05, -0.24809});
  expectNear(r.translation(), {0, -0.05, -0.24809});
  EXPECT_TRUE(l.linear().isApprox(Eigen::Matrix3d::Identity(), 1e-12));
  EXPECT_TRUE(r.linear().isApprox(Eigen::Matrix3d::Identity(), 1e-12));
  expectNear(torsoToAnkle(j, BodySide::Left).translation(), {0, 0.05, -0.2029});
}

TEST(Kinematics, ZeroPoseHeadAndCameras) {
  const JointArray j = zeros();
  expectNear(torsoToHead(j).translation(), {0, 0, 0.2115});
  const auto top = torsoToCamera(j, CameraId::Top);
  const auto bottom = torsoToCamera(j, CameraId::Bottom);
  expectNear(top.translation(), {0.05871, 0, 0.2115 + 0.06364});
  expectNear(bottom.translation(), {0.05071, 0, 0.2115 + 0.01774});
  // Pitched down: the optical axis (camera x) points below the horizontal.
  const double a = 39.7 * std::numbers::pi / 180;
  expectNear(bottom.linear().col(0), {std::cos(a), 0, -std::sin(a)});
  expectNear(bottom.linear().col(1), {0, 1, 0});  // image left = robot left
}

TEST(Kinematics, HeadYawAndPitch) {
  JointArray j = zeros();
  j[HeadYaw] = std::numbers::pi / 2;
  expectNear(torsoToCamera(j, CameraId::Top).translation(), {0, 0.05871, 0.27514});
  // HeadPitch > 0 looks down: the camera moves forward/down about the joint.
  j[HeadYaw] = 0;
  const double p = 0.3;
  j[HeadPitch] = p;
  const Eigen::Vector3d expected(0.05871 * std::cos(p) + 0.06364 * std::sin(p), 0,
                                 0.2115 - 0.05871 * std::sin(p) + 0.06364 * std::cos(p));
  expectNear(torsoToCamera(j, CameraId::Top).translation(), expected);
  EXPECT_LT(torsoToCamera(j, CameraId::Top).linear().col(0).z(), -std::sin(p));  // looks further down
}

TEST(Kinematics, KneeBentFlatFoot) {
  JointArray j = zeros();
  const double a = 0.5;
  for (auto [hip, knee, ankle] : {std::tuple{LHipPitch, LKneePitch, LAnklePitch},
                                  std::tuple{RHipPitch, RKneePitch, RAnklePitch}}) {
    j[hip] = -a;
    j[knee] = 2 * a;
    j[ankle] = -a;
  }
  for (BodySide side : {BodySide::Left, BodySide::Right}) {
    const double y = side == BodySide::Left ? 0.05 : -0.05;
    const auto sole = torsoToSole(j, side);
    expectNear(sole.translation(), {(0.1 - 0.1029) * std::sin(a), y, -(0.2029 * std::cos(a) + 0.04519)});
    EXPECT_TRUE(sole.linear().isApprox(Eigen::Matrix3d::Identity(), 1e-12));
    // The knee is in front of the hip: the ankle lies on the thigh's forward arc.
    expectNear(torsoToAnkle(j, side).translation(),
               {0.1 * std::sin(a) - 0.1029 * std::sin(a), y, -0.2029 * std::cos(a)});
  }
  EXPECT_NEAR(torsoHeightAboveGround(j, 0, 0), 0.2029 * std::cos(a) + 0.04519, kTol);
}

TEST(Kinematics, HipYawPitchAxes) {
  JointArray j = zeros();
  const double t = 0.4;
  j[LHipYawPitch] = t;
  const Eigen::Vector3d down(0, 0, -kLeg);
  const Eigen::Vector3d l = Eigen::AngleAxisd(t, Eigen::Vector3d(0, 1, -1).normalized()) * down;
  const Eigen::Vector3d r = Eigen::AngleAxisd(t, Eigen::Vector3d(0, 1, 1).normalized()) * down;
  expectNear(torsoToSole(j, BodySide::Left).translation(), l + Eigen::Vector3d(0, 0.05, 0));
  expectNear(torsoToSole(j, BodySide::Right).translation(), r + Eigen::Vector3d(0, -0.05, 0));
  // One angle, mirrored axes: the feet yaw in opposite directions.
  const auto ls = torsoToSole(j, BodySide::Left), rs = torsoToSole(j, BodySide::Right);
  EXPECT_NEAR(ls.linear().col(0).y(), -rs.linear().col(0).y(), 1e-12);
}

TEST(Kinematics, LegsMirror) {
  // Same HipYawPitch, mirrored rolls, same pitches: the right leg is the left's mirror image.
  JointArray j = zeros();
  j[LHipYawPitch] = -0.3;
  j[LHipRoll] = 0.2;
  j[RHipRoll] = -0.2;
  j[LHipPitch] = j[RHipPitch] = -0.6;
  j[LKneePitch] = j[RKneePitch] = 1.1;
  j[LAnklePitch] = j[RAnklePitch] = -0.45;
  j[LAnkleRoll] = -0.1;
  j[RAnkleRoll] = 0.1;
  const Eigen::Matrix3d m = Eigen::Vector3d(1, -1, 1).asDiagonal();
  const auto l = torsoToSole(j, BodySide::Left), r = torsoToSole(j, BodySide::Right);
  expectNear(m * l.translation(), r.translation());
  EXPECT_TRUE((m * l.linear() * m).isApprox(r.linear(), 1e-12));
}

TEST(Kinematics, Hands) {
  JointArray j = zeros();
  const double reach = 0.105 + 0.05595 + 0.05775;
  expectNear(torsoToHand(j, BodySide::Left).translation(), {reach, 0.098 + 0.015, 0.185 + 0.01231});
  expectNear(torsoToHand(j, BodySide::Right).translation(), {reach, -0.098 - 0.015, 0.185 + 0.01231});
  j[LShoulderPitch] = std::numbers::pi / 2;  // arm hanging down
  expectNear(torsoToHand(j, BodySide::Left).translation(), {0.01231, 0.098 + 0.015, 0.185 - reach});
}

TEST(Kinematics, TorsoHeightUpright) {
  const JointArray j = zeros();
  EXPECT_NEAR(torsoHeightAboveGround(j, 0, 0), kLeg, kTol);
  EXPECT_NEAR(torsoHeightAboveGround(j, 0, 0, SoleContact::Centre), kLeg, kTol);
  const auto t = robotToTorso(j, 0, 0);
  expectNear(t.translation(), {0, 0, kLeg});
}

TEST(Kinematics, TorsoHeightTilted) {
  const JointArray j = zeros();
  // Leaning forward by p with straight legs: the whole rigid body tilts about the ground.
  const double p = 0.1;
  EXPECT_NEAR(torsoHeightAboveGround(j, 0, p, SoleContact::Centre), kLeg * std::cos(p), kTol);
  EXPECT_NEAR(torsoHeightAboveGround(j, 0, p), kLeg * std::cos(p) + 0.1 * std::sin(p), kTol);  // toes
  EXPECT_NEAR(torsoHeightAboveGround(j, 0, -p), kLeg * std::cos(p) + 0.05 * std::sin(p), kTol);  // heels
  // Rolled to the left (roll > 0 lowers the right side): the right foot's outer edge carries it.
  const double r = 0.08;
  EXPECT_NEAR(torsoHeightAboveGround(j, r, 0, SoleContact::Centre), 0.05 * std::sin(r) + kLeg * std::cos(r), kTol);
  EXPECT_NEAR(torsoHeightAboveGround(j, r, 0), (0.05 + 0.05002) * std::sin(r) + kLeg * std::cos(r), kTol);
  // The robot frame's torso orientation is Ry(pitch) Rx(roll).
  const auto t = robotToTorso(j, r, p);
  EXPECT_TRUE(t.linear().isApprox(rotY(p) * rotX(r), 1e-12));
}

TEST(Kinematics, LiftedFootDoesNotCarry) {
  JointArray j = zeros();
  j[RHipPitch] = -0.4;  // swing leg bent up: shorter
  j[RKneePitch] = 0.8;
  j[RAnklePitch] = -0.4;
  EXPECT_NEAR(torsoHeightAboveGround(j, 0, 0), kLeg, kTol);
}

}  // namespace
}  // namespace nao
