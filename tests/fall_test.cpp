// Falling in the simulator (ground truth): pushed over onto its front or its back, the robot
// falls the way it was pushed, goes soft while falling (safe fall), lies still and, asked to
// stand, starts getting up (the get-up's key frames run). Whether it gets up is getup_test's
// (pending) business. NAO_TEST_QUICK shortens the time spent lying.
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <gtest/gtest.h>

#include "controllers/GetUp.h"
#include "controllers/Kinematics.h"
#include "robot/ForwardKinematics.h"
#include "scenarios/GetUpEval.h"

namespace nao {
namespace {

TEST(GetUp, SquatHasTheComAboveFlatSoles) {
  const GetUp::Params params;
  for (const GetUp::Squat& squat : {params.frontSquat, params.backSquat}) {
    const JointArray j = GetUp::squatPosture(squat);
    const Eigen::Isometry3d l = torsoToSole(j, BodySide::Left), r = torsoToSole(j, BodySide::Right);
    // Both soles flat on one floor: parallel normals, the same height along them.
    const Eigen::Vector3d up = l.linear().col(2);
    EXPECT_GT(up.dot(r.linear().col(2)), std::cos(2 * M_PI / 180));
    // (the shared HipYawPitch leaves a few mm)
    EXPECT_NEAR(up.dot(l.translation() - r.translation()), 0, 0.005);
    // The COM above the soles' midpoint (within a few cm, inside the wide stance), the torso
    // leaning as asked.
    const Eigen::Vector3d rel = centerOfMass(j) - (l.translation() + r.translation()) / 2;
    const Eigen::Vector3d horizontal = rel - up * up.dot(rel);
    EXPECT_LT(horizontal.norm(), 0.04);
    EXPECT_NEAR(std::acos(std::clamp(up.z(), -1.0, 1.0)), std::abs(squat.pitch), 0.03);
  }
}

TEST(Fall, LyingDirectionFollowsTheTorsoAxes) {
  constexpr double d = M_PI / 180;
  EXPECT_EQ(lyingDirection(0, 85 * d), FallDirection::Front);
  EXPECT_EQ(lyingDirection(0, -85 * d), FallDirection::Back);
  EXPECT_EQ(lyingDirection(80 * d, 0), FallDirection::Right);
  EXPECT_EQ(lyingDirection(-80 * d, 0), FallDirection::Left);
  // On the face with the hips up (torso tilted past 90 deg): pitch ~56, roll ~180 deg.
  EXPECT_EQ(lyingDirection(175 * d, 56 * d), FallDirection::Front);
  // On the face, rolled 30 deg onto the right side: roll 112, pitch 56 (a fall the old
  // roll-versus-pitch rule called "right").
  EXPECT_EQ(lyingDirection(112 * d, 56 * d), FallDirection::Front);
}

TEST(Fall, FallsTheWayItIsPushedAndStartsGettingUp) {
  for (FallDirection side : {FallDirection::Front, FallDirection::Back}) {
    sim::GetUpTrialOptions o;
    o.side = side;
    o.seed = 5;
    o.timeLimit = std::getenv("NAO_TEST_QUICK") ? 3 : 6;
    const sim::GetUpTrialResult r = sim::runGetUp(o);
    std::printf("%s: fell that way %d, %d get-up attempts\n", fallDirectionName(side), r.fellOnRequestedSide, r.attempts);
    EXPECT_TRUE(r.fellOnRequestedSide);
    EXPECT_GE(r.attempts, 1);
  }
}

}  // namespace
}  // namespace nao
