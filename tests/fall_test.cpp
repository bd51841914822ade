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
#include "robot/Blackboard.h"
#include "robot/JointRequest.h"
#include "scenarios/GetUpEval.h"
#include "scenarios/WalkEval.h"
#include "sim/World.h"

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


// The safe fall, against the simulator's truth: pushed over from the stand, the robot knows it
// is falling while its torso is still high (0.1 s or more before it lies), and from then until
// it lies its joints are soft (stiffness <= 0.5) with the arms where they catch the fall:
// forward when falling forward, along the body when falling backward, the head turned away
// from the impact.
TEST(Fall, DetectsTheFallEarlyAndFallsSoftWithTheArmsOut) {
  for (FallDirection side : {FallDirection::Front, FallDirection::Back}) {
    SCOPED_TRACE(fallDirectionName(side));
    sim::MotionSimOptions so;
    so.seed = 11;
    sim::MotionSim sim(so);
    const MotionRequest stand;
    for (int i = 0; i < static_cast<int>((so.params.transitionTime + 0.5) / 0.012); ++i) ASSERT_TRUE(sim.cycle(stand));
    const double standingZ = sim.world().torsoPose(0).translation().z();
    const bool front = side == FallDirection::Front;
    const double heading = sim.truePose().z() + (front ? 0.0 : M_PI);
    sim.world().pushRobot(0, 8.0 * Eigen::Vector3d(std::cos(heading), std::sin(heading), 0));
    double detectedAt = -1, detectedZ = 0, lyingAt = -1;
    int softCycles = 0, softFailures = 0, armFailures = 0;
    for (int i = 0; i < static_cast<int>(3.0 / 0.012) && lyingAt < 0; ++i) {
      ASSERT_TRUE(sim.cycle(stand));
      const FallState& fall = sim.fallState();
      if (detectedAt < 0 && (fall.falling || fall.fallen)) {
        detectedAt = sim.time();
        detectedZ = sim.world().torsoPose(0).translation().z();
        EXPECT_EQ(fall.direction, side);
      }
      if (sim.trueFallen() && sim.world().torsoPose(0).translation().z() < 0.15) lyingAt = sim.time();
      if (detectedAt < 0 || lyingAt >= 0) continue;
      // Falling, until the impact: what the motion engine asks of the joints.
      const JointRequest& request = sim.program().blackboard().read<JointRequest>();
      ++softCycles;
      softFailures += *std::max_element(request.stiffness.begin(), request.stiffness.end()) > 0.5;
      const double shoulders = 0.5 * (request.position[LShoulderPitch] + request.position[RShoulderPitch]);
      armFailures += front ? !(shoulders < 0.5 && request.position[HeadPitch] < 0)
                           : !(shoulders > 1.2 && request.position[HeadPitch] > 0);
    }
    std::printf("%s: detected %.2f s before lying, torso %.2f m high then (%.2f standing); %d falling cycles\n",
                fallDirectionName(side), lyingAt - detectedAt, detectedZ, standingZ, softCycles);
    ASSERT_GT(detectedAt, 0);
    ASSERT_GT(lyingAt, 0);
    EXPECT_GE(lyingAt - detectedAt, 0.09);  // 8 cycles or more
    EXPECT_GT(detectedZ, 0.6 * standingZ);
    EXPECT_GE(softCycles, 5);
    EXPECT_EQ(softFailures, 0);
    EXPECT_EQ(armFailures, 0);
  }
}

}  // namespace
}  // namespace nao
