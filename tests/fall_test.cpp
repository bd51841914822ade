// Falling in the simulator (ground truth): pushed over onto its front or its back, the robot
// falls the way it was pushed, goes soft while falling (safe fall), lies still and, asked to
// stand, starts getting up (the get-up's key frames run). Whether it gets up is getup_test's
// (pending) business. NAO_TEST_QUICK shortens the time spent lying.
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
  const JointArray squat = GetUp::squatPosture();
  const Eigen::Isometry3d sole = torsoToSole(squat, BodySide::Left);
  const Eigen::Matrix3d r = sole.linear().transpose();  // torso in the sole frame
  const Eigen::Vector3d com = r * (centerOfMass(squat) - sole.translation());
  EXPECT_GT(com.x(), -0.02);
  EXPECT_LT(com.x(), 0.05);
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
