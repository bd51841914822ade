// MotionEngine alone, with servos that follow the request: it moves into the walk's stand
// posture, applies the head's request, raises and lowers an arm over the stand, goes soft when
// the fall detector says the robot lies.
#include <gtest/gtest.h>

#include "controllers/Walk.h"
#include "controllers/modules/MotionEngine.h"
#include "tests/support/ModuleHarness.h"

namespace nao {
namespace {

using testing::ModuleHarness;
constexpr double kDt = 0.012;

void runFor(ModuleHarness& h, double seconds, double& t) {
  for (int i = 0; i < static_cast<int>(std::lround(seconds / kDt)); ++i) {
    SensorFrame& f = h.input<SensorFrame>();
    f.time = (t += kDt);
    h.run();
    f.joints.position = h.get<JointRequest>().position;
  }
}

ModuleHarness standingEngine() {
  ModuleHarness h("MotionEngine");
  SensorFrame f;
  f.fsr.weight.fill(4.5 / 8);
  HeadJointRequest head;
  head.yaw = 0.3;
  h.fix(f).fix(FallState{}).fix(MotionRequest{}).fix(head).fix(ArmMotionRequest{});
  return h;
}

TEST(MotionEngineModule, StandsUpIntoTheWalksPostureAndTurnsTheHead) {
  ModuleHarness h = standingEngine();
  double t = 0;
  const JointArray stand = Walk().standPosture();
  runFor(h, 0.4, t);  // half-way through the transition
  const double knee = h.get<JointRequest>().position[LKneePitch];
  EXPECT_GT(knee, 0.05 * stand[LKneePitch]);
  EXPECT_LT(knee, 0.95 * stand[LKneePitch]);
  runFor(h, 1.0, t);
  const JointRequest& out = h.get<JointRequest>();
  for (int j : {LHipPitch, LKneePitch, RHipPitch, RKneePitch}) EXPECT_NEAR(out.position[j], stand[j], 0.05) << j;
  // The ankles carry the walk's sag compensation (the torque the servos must hold): 3 deg more.
  for (int j : {LAnklePitch, RAnklePitch}) EXPECT_NEAR(out.position[j], stand[j], 0.08) << j;
  EXPECT_NEAR(out.position[HeadYaw], 0.3, 1e-9);
  EXPECT_GT(out.stiffness[LKneePitch], 0.5);
  EXPECT_EQ(h.get<MotionInfo>().motion, MotionType::Stand);
  EXPECT_TRUE(h.get<MotionInfo>().upright);
  EXPECT_NEAR(h.get<Odometry>().pose.x, 0, 0.01);
}

TEST(MotionEngineModule, GoesSoftWhenTheRobotLies) {
  ModuleHarness h = standingEngine();
  double t = 0;
  runFor(h, 1.2, t);
  FallState down;
  down.fallen = true;
  down.direction = FallDirection::Front;
  down.fallTime = t;
  h.input<FallState>() = down;
  h.input<MotionRequest>().motion = MotionType::PlayDead;  // stay down: no get-up
  runFor(h, 0.1, t);
  EXPECT_FALSE(h.get<MotionInfo>().upright);
  for (double s : h.get<JointRequest>().stiffness) EXPECT_LE(s, 0.5);
}

TEST(MotionEngineModule, RaisesTheRequestedArmOverTheStandAndLowersIt) {
  ModuleHarness h = standingEngine(), plain = standingEngine();  // plain: the same stand, no arm
  double t = 0, tPlain = 0;
  runFor(h, 1.2, t);
  runFor(plain, 1.2, tPlain);
  const JointArray down = h.get<JointRequest>().position;
  h.input<ArmMotionRequest>().raise = ArmMotionRequest::Arm::Left;
  runFor(h, 0.3, t);  // half-way: moving, not there
  EXPECT_LT(h.get<JointRequest>().position[LShoulderPitch], down[LShoulderPitch] - 0.3);
  EXPECT_FALSE(h.get<MotionInfo>().armRaised);
  runFor(h, 0.4, t);
  runFor(plain, 0.7, tPlain);
  const auto raised = nao::MotionEngine::raisedArm(ArmMotionRequest::Arm::Left);
  const JointRequest& out = h.get<JointRequest>();
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(out.position[LShoulderPitch + k], raised[k], 1e-9) << k;
  // The rest is the stand's own: the other arm exactly, the legs within the stand's balance.
  const JointArray& stand = plain.get<JointRequest>().position;
  for (int j = RShoulderPitch; j <= RWristYaw; ++j) EXPECT_NEAR(out.position[j], stand[j], 1e-9) << j;
  for (int j : {LHipPitch, LKneePitch, LAnklePitch, RHipPitch, RKneePitch, RAnklePitch})
    EXPECT_NEAR(out.position[j], stand[j], 0.02) << j;
  EXPECT_TRUE(h.get<MotionInfo>().armRaised);
  EXPECT_GT(raised[1], 0);  // the left arm's roll is outwards, the right one mirrors it
  EXPECT_NEAR(nao::MotionEngine::raisedArm(ArmMotionRequest::Arm::Right)[1], -raised[1], 1e-12);
  h.input<ArmMotionRequest>().raise = ArmMotionRequest::Arm::None;
  runFor(h, 0.7, t);
  runFor(plain, 0.7, tPlain);
  EXPECT_FALSE(h.get<MotionInfo>().armRaised);
  EXPECT_NEAR(h.get<JointRequest>().position[LShoulderPitch], plain.get<JointRequest>().position[LShoulderPitch], 1e-9);
}

TEST(MotionEngineModule, ParametersFromTheContext) {
  MotionEngine::Params p;
  p.transitionTime = 0.2;
  ModuleHarness h("MotionEngine", ModuleContext{"", "", {{"MotionEngine", p}}});
  SensorFrame f;
  f.fsr.weight.fill(4.5 / 8);
  h.fix(f).fix(FallState{}).fix(MotionRequest{}).fix(HeadJointRequest{}).fix(ArmMotionRequest{});
  double t = 0;
  runFor(h, 0.3, t);  // past the shorter transition: the stand posture
  EXPECT_NEAR(h.get<JointRequest>().position[LKneePitch], Walk().standPosture()[LKneePitch], 0.05);
}

}  // namespace
}  // namespace nao
