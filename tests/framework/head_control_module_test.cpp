// HeadControl alone, with servos that follow the command: the head moves towards the
// requested angles no faster than its limits, stops there, and never leaves the joint limits.
#include <gtest/gtest.h>

#include <cmath>

#include "controllers/Kinematics.h"
#include "controllers/modules/HeadControl.h"
#include "tests/support/ModuleHarness.h"

namespace nao {
namespace {

using testing::ModuleHarness;
constexpr double kDt = 0.012;

// Runs `seconds` of cycles; the joints read what was commanded the cycle before.
// Returns the largest yaw and pitch step per cycle.
Eigen::Vector2d runFor(ModuleHarness& h, double seconds, double& t) {
  Eigen::Vector2d maxStep = Eigen::Vector2d::Zero();
  for (int i = 0; i < static_cast<int>(std::lround(seconds / kDt)); ++i) {
    SensorFrame& f = h.input<SensorFrame>();
    const Eigen::Vector2d before(f.joints.position[HeadYaw], f.joints.position[HeadPitch]);
    f.time = (t += kDt);
    h.run();
    const HeadJointRequest& r = h.get<HeadJointRequest>();
    maxStep = maxStep.cwiseMax(Eigen::Vector2d(std::abs(r.yaw - before.x()), std::abs(r.pitch - before.y())));
    EXPECT_GE(r.yaw, jointMin(HeadYaw) - 1e-12);
    EXPECT_LE(r.yaw, jointMax(HeadYaw) + 1e-12);
    EXPECT_GE(r.pitch, jointMin(HeadPitch) - 1e-12);
    EXPECT_LE(r.pitch, jointMax(HeadPitch) + 1e-12);
    f.joints.position[HeadYaw] = r.yaw;
    f.joints.position[HeadPitch] = r.pitch;
  }
  return maxStep;
}

ModuleHarness harness(double yaw, double pitch, const ModuleContext& context = {}) {
  ModuleHarness h("HeadControl", context);
  HeadMotionRequest request;
  request.mode = HeadMotionRequest::Mode::Angles;
  request.yaw = yaw;
  request.pitch = pitch;
  h.fix(SensorFrame{}).fix(request).fix(TorsoState{});
  return h;
}

TEST(HeadControlModule, MovesTowardsTheRequestedAngleWithinItsSpeed) {
  ModuleHarness h = harness(0.5, 0.2);
  double t = 0;
  runFor(h, 0.05, t);
  const double early = h.get<HeadJointRequest>().yaw;
  EXPECT_GT(early, 0.0);
  EXPECT_LT(early, 0.5);
  const Eigen::Vector2d step = runFor(h, 1.0, t);
  const HeadControl::Params p;
  EXPECT_LE(step.x(), p.maxYawSpeed * kDt + 1e-9);
  EXPECT_LE(step.y(), p.maxPitchSpeed * kDt + 1e-9);
  EXPECT_NEAR(h.get<HeadJointRequest>().yaw, 0.5, 1e-9);
  EXPECT_NEAR(h.get<HeadJointRequest>().pitch, 0.2, 1e-9);
  runFor(h, 0.2, t);
  EXPECT_TRUE(h.as<modules::HeadControl>().control().settled());
}

TEST(HeadControlModule, StaysWithinTheJointLimits) {
  ModuleHarness h = harness(5.0, -3.0);
  double t = 0;
  runFor(h, 2.0, t);
  EXPECT_NEAR(h.get<HeadJointRequest>().yaw, jointMax(HeadYaw), 1e-9);
  h.input<HeadMotionRequest>().yaw = -5.0;
  h.input<HeadMotionRequest>().pitch = 3.0;
  runFor(h, 3.0, t);
  EXPECT_NEAR(h.get<HeadJointRequest>().yaw, jointMin(HeadYaw), 1e-9);
  EXPECT_LE(h.get<HeadJointRequest>().pitch, jointMax(HeadPitch));
}

TEST(HeadControlModule, SlowerWithItsParameters) {
  HeadControl::Params slow;
  slow.maxYawSpeed = 0.5;
  ModuleHarness h = harness(1.0, 0, ModuleContext{"", "", {{"HeadControl", slow}}});
  double t = 0;
  const Eigen::Vector2d step = runFor(h, 1.0, t);
  EXPECT_LE(step.x(), 0.5 * kDt + 1e-9);
  EXPECT_LT(h.get<HeadJointRequest>().yaw, 0.55);
}

}  // namespace
}  // namespace nao
