// Inverse kinematics of the NAO's legs (shared HipYawPitch) and arms, by round trips through
// forward kinematics over the reachable space, and the mass model against the simulator's model.
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include "controllers/Kinematics.h"
#include "controllers/StandController.h"
#include "robot/ForwardKinematics.h"
#include "robot/RobotDimensions.h"
#include "sim/World.h"

namespace nao {
namespace {

constexpr double kPosTol = 1e-6;   // m
constexpr double kRotTol = 1e-6;   // rad

double rotationError(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}

double uniform(std::mt19937& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

// A random leg posture well inside the joint ranges (away from the stretched knee).
LegJoints randomLeg(std::mt19937& rng, BodySide side, double hyp) {
  const double s = side == BodySide::Left ? 1.0 : -1.0;
  LegJoints l;
  l.hipYawPitch = hyp;
  l.hipRoll = s * uniform(rng, -0.3, 0.6);
  l.hipPitch = uniform(rng, -1.3, 0.4);
  l.knee = uniform(rng, 0.15, 2.0);
  l.anklePitch = uniform(rng, -1.0, 0.8);
  l.ankleRoll = s * uniform(rng, -0.35, 0.35);
  return l;
}

TEST(LegIK, FreeHipYawPitchRoundTrip) {
  std::mt19937 rng(1);
  for (BodySide side : {BodySide::Left, BodySide::Right}) {
    for (int i = 0; i < 2000; ++i) {
      JointArray j{};
      setLeg(j, side, randomLeg(rng, side, uniform(rng, -1.0, 0.7)));
      const Eigen::Isometry3d target = torsoToSole(j, side);
      LegJoints out;
      ASSERT_TRUE(legIK(target, side, out)) << "sample " << i;
      JointArray k{};
      setLeg(k, side, out);
      const Eigen::Isometry3d got = torsoToSole(k, side);
      EXPECT_LT((got.translation() - target.translation()).norm(), kPosTol) << "sample " << i;
      EXPECT_LT(rotationError(got.linear(), target.linear()), kRotTol) << "sample " << i;
    }
  }
}

TEST(LegIK, CoupledHipYawPitchRoundTrip) {
  // Poses both legs reach with one HipYawPitch angle: legsIK finds them exactly.
  std::mt19937 rng(2);
  for (int i = 0; i < 2000; ++i) {
    const double hyp = uniform(rng, -0.9, 0.6);
    JointArray j{};
    setLeg(j, BodySide::Left, randomLeg(rng, BodySide::Left, hyp));
    setLeg(j, BodySide::Right, randomLeg(rng, BodySide::Right, hyp));
    const auto l = torsoToSole(j, BodySide::Left), r = torsoToSole(j, BodySide::Right);
    JointArray k{};
    ASSERT_TRUE(legsIK(l, r, k)) << "sample " << i;
    EXPECT_NEAR(k[LHipYawPitch], hyp, 1e-6);
    for (auto [side, target] : {std::pair{BodySide::Left, l}, std::pair{BodySide::Right, r}}) {
      const auto got = torsoToSole(k, side);
      EXPECT_LT((got.translation() - target.translation()).norm(), kPosTol);
      EXPECT_LT(rotationError(got.linear(), target.linear()), kRotTol);
    }
  }
}

TEST(LegIK, FixedHipYawPitchKeepsPositionAndSoleNormal) {
  // Feet yawed the same way (not reachable with one HipYawPitch): position and sole normal
  // are still exact; only the yaw about the normal differs.
  std::mt19937 rng(3);
  for (int i = 0; i < 1000; ++i) {
    const double yaw = uniform(rng, -0.3, 0.3);
    for (BodySide side : {BodySide::Left, BodySide::Right}) {
      const double s = side == BodySide::Left ? 1.0 : -1.0;
      Eigen::Isometry3d target = Eigen::Isometry3d::Identity();
      target.translation() = Eigen::Vector3d(uniform(rng, -0.05, 0.06), s * 0.05 + uniform(rng, -0.02, 0.025) * s,
                                             -uniform(rng, 0.19, 0.225));
      target.linear() = rotZ(yaw) * rotY(uniform(rng, -0.15, 0.15)) * rotX(uniform(rng, -0.1, 0.1));
      LegJoints out;
      ASSERT_TRUE(legIKFixedHipYawPitch(target, side, uniform(rng, -0.25, 0.1), out)) << "sample " << i;
      JointArray k{};
      setLeg(k, side, out);
      const auto got = torsoToSole(k, side);
      EXPECT_LT((got.translation() - target.translation()).norm(), kPosTol);
      EXPECT_LT((got.linear().col(2) - target.linear().col(2)).norm(), kRotTol);
    }
  }
}

TEST(LegIK, StandingPostureAndUnreachableTargets) {
  // The walk's typical pose: sole flat 0.225 m below the hip, under the hip.
  Eigen::Isometry3d target = Eigen::Isometry3d::Identity();
  target.translation() = Eigen::Vector3d(0, 0.05, -0.225);
  LegJoints out;
  ASSERT_TRUE(legIK(target, BodySide::Left, out));
  EXPECT_NEAR(out.hipYawPitch, 0, 1e-9);
  EXPECT_NEAR(out.hipRoll, 0, 1e-9);
  EXPECT_NEAR(out.ankleRoll, 0, 1e-9);
  EXPECT_NEAR(out.hipPitch + out.knee + out.anklePitch, 0, 1e-9);  // sole parallel to the torso
  EXPECT_GT(out.knee, 0.5);
  // Too far: false, and the leg is stretched towards the target.
  target.translation() = Eigen::Vector3d(0, 0.05, -0.4);
  EXPECT_FALSE(legIK(target, BodySide::Left, out));
  EXPECT_NEAR(out.knee, 0, 1e-6);
  JointArray k{};
  setLeg(k, BodySide::Left, out);
  EXPECT_NEAR(torsoToSole(k, BodySide::Left).translation().z(), -dims::kLegLength, 1e-6);
  // Beyond a joint limit (foot far to the inside): false, angles within the limits.
  target.translation() = Eigen::Vector3d(0, -0.12, -0.2);
  EXPECT_FALSE(legIK(target, BodySide::Left, out));
  EXPECT_GE(out.hipRoll, jointMin(LHipRoll) - 1e-12);
}

TEST(ArmIK, RoundTrip) {
  std::mt19937 rng(4);
  int reached = 0;
  for (BodySide side : {BodySide::Left, BodySide::Right}) {
    const double s = side == BodySide::Left ? 1.0 : -1.0;
    const Joint roll = side == BodySide::Left ? LShoulderRoll : RShoulderRoll;
    const Joint elbow = side == BodySide::Left ? LElbowRoll : RElbowRoll;
    for (int i = 0; i < 2000; ++i) {
      ArmJoints a;
      a.shoulderPitch = uniform(rng, -2.0, 2.0);
      a.shoulderRoll = uniform(rng, jointMin(roll) + 0.02, jointMax(roll) - 0.02);
      a.elbowYaw = uniform(rng, -2.0, 2.0);
      a.elbowRoll = -s * uniform(rng, 0.1, 1.5);
      a.wristYaw = uniform(rng, -1.5, 1.5);
      ASSERT_GE(a.elbowRoll, jointMin(elbow));
      JointArray j{};
      setArm(j, side, a);
      const Eigen::Vector3d hand = torsoToHand(j, side).translation();
      ArmJoints out;
      if (!armIK(hand, side, a.elbowYaw, a.wristYaw, out)) continue;  // the other elbow branch may be out of range
      ++reached;
      JointArray k{};
      setArm(k, side, out);
      EXPECT_LT((torsoToHand(k, side).translation() - hand).norm(), kPosTol) << "sample " << i;
    }
  }
  EXPECT_GT(reached, 3800);  // nearly every sample: the solution is unique in the joint ranges
  // Out of reach.
  ArmJoints out;
  EXPECT_FALSE(armIK(Eigen::Vector3d(0.5, 0.1, 0.2), BodySide::Left, 0, 0, out));
}

TEST(MassModel, MatchesTheSimulatedRobot) {
  EXPECT_NEAR(totalMass(), 5.35946, 1e-5);
  sim::SceneSpec spec;
  sim::World world(spec);
  std::mt19937 rng(5);
  for (int i = 0; i < 50; ++i) {
    JointArray j = StandController::standPosture();
    for (int k = 0; k < NumJoints; ++k)
      j[k] = clampToLimits(static_cast<Joint>(k), j[k] + uniform(rng, -0.4, 0.4));
    j[LHand] = j[RHand] = 0;
    world.placeRobot(0, Eigen::Vector3d(0, 0, 0.4), j);
    const mjModel* m = world.model();
    const mjData* d = world.data();
    const int torso = mj_name2id(m, mjOBJ_BODY, "r0/torso");
    ASSERT_GE(torso, 0);
    const Eigen::Vector3d com(d->subtree_com + 3 * torso);
    const Eigen::Vector3d expected = world.torsoPose(0) * centerOfMass(j);
    EXPECT_LT((com - expected).norm(), 2e-4) << "sample " << i;  // the model's 0.2 g finger bodies
  }
}

}  // namespace
}  // namespace nao
