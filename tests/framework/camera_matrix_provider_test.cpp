// CameraMatrixProvider and TorsoMatrixProvider alone: the matrices are the camera model's for
// the posture, IMU and calibration; the intrinsics follow the delivered image size.
#include <gtest/gtest.h>

#include "controllers/Walk.h"
#include "controllers/modules/CameraMatrixProvider.h"
#include "controllers/modules/TorsoMatrixProvider.h"
#include "representations/perception/FallState.h"
#include "robot/ForwardKinematics.h"
#include "tests/support/ModuleHarness.h"

namespace nao {
namespace {

using testing::ModuleHarness;

SensorFrame standing(double roll, double pitch, double headYaw) {
  SensorFrame f;
  f.joints.position = Walk().standPosture();
  f.joints.position[HeadYaw] = headYaw;
  f.joints.position[HeadPitch] = 0.2;
  f.inertial.angle = {roll, pitch};
  return f;
}

void expectSame(const CameraMatrix& a, const CameraMatrix& b) {
  EXPECT_LT((a.pose.matrix() - b.pose.matrix()).norm(), 1e-12);
  EXPECT_EQ(a.intrinsics.width, b.intrinsics.width);
  EXPECT_EQ(a.intrinsics.height, b.intrinsics.height);
  EXPECT_DOUBLE_EQ(a.intrinsics.fx, b.intrinsics.fx);
  EXPECT_DOUBLE_EQ(a.intrinsics.cy, b.intrinsics.cy);
}

TEST(TorsoMatrixProvider, TorsoFromImuAndLegs) {
  ModuleHarness h = ModuleHarness::make<modules::TorsoMatrixProvider>();
  const SensorFrame f = standing(0.02, 0.1, 0);
  h.fix(f).run();
  const Eigen::Isometry3d want = robotToTorso(f.joints.position, 0.02, 0.1);
  EXPECT_LT((h.get<TorsoState>().robotToTorso.matrix() - want.matrix()).norm(), 1e-12);
  // Leaning forward: the torso's x axis points down a little.
  EXPECT_LT(h.get<TorsoState>().robotToTorso.linear()(2, 0), -0.09);
}

TEST(CameraMatrixProvider, MatchesTheCameraModelForAKnownPosture) {
  ModuleHarness h("CameraMatrixProvider");
  const SensorFrame f = standing(0.01, -0.03, 0.4);
  const Eigen::Isometry3d torso = robotToTorso(f.joints.position, 0.01, -0.03);
  CameraCalibration calib;
  calib.bodyPitch = 0.01;
  calib.topRoll = -0.02;
  calib.bottomPitch = 0.015;
  h.fix(f).fix(TorsoState{torso}).fix(calib).fix(CameraImages{}).run();
  for (CameraId cam : {CameraId::Top, CameraId::Bottom})
    expectSame(h.get<CameraMatrices>().matrix[static_cast<int>(cam)],
               computeCameraMatrix(f.joints.position, torso, cam, calib, CameraIntrinsics::nominal(cam)));
  // The top camera looks along the head's yaw, above the bottom one.
  const auto& top = h.get<CameraMatrices>().matrix[0];
  EXPECT_NEAR(std::atan2(top.pose.linear()(1, 0), top.pose.linear()(0, 0)), 0.4, 0.05);
  EXPECT_GT(top.pose.translation().z(), h.get<CameraMatrices>().matrix[1].pose.translation().z());
}

TEST(CameraMatrixProvider, IntrinsicsFollowTheDeliveredImageSize) {
  ModuleHarness h = ModuleHarness::make<modules::CameraMatrixProvider>();
  const SensorFrame f = standing(0, 0, 0);
  const Eigen::Isometry3d torso = robotToTorso(f.joints.position, 0, 0);
  CameraImages images;
  CameraImage small;
  small.camera = CameraId::Bottom;
  small.width = 320;
  small.height = 240;
  small.yuyv.assign(320 * 240 * 2, 0);
  images.latest[1] = small;
  h.fix(f).fix(TorsoState{torso}).fix(CameraCalibration{}).fix(images).run();
  const auto& m = h.get<CameraMatrices>().matrix;
  expectSame(m[1], computeCameraMatrix(f.joints.position, torso, CameraId::Bottom, {}, CameraIntrinsics::fromFovY(320, 240)));
  expectSame(m[0], computeCameraMatrix(f.joints.position, torso, CameraId::Top, {}, CameraIntrinsics::nominal(CameraId::Top)));
  // The size is the module's own state: it holds when no image arrives, and its inputs are
  // untouched (it cannot write them any more).
  h.input<CameraImages>() = CameraImages{};
  h.run();
  EXPECT_EQ(h.get<CameraMatrices>().matrix[1].intrinsics.width, 320);
  EXPECT_EQ(h.as<modules::CameraMatrixProvider>().intrinsics()[1].height, 240);
}

TEST(ModuleHarness, RefusesWhatTheModuleDidNotDeclare) {
  ModuleHarness h = ModuleHarness::make<modules::CameraMatrixProvider>();
  EXPECT_THROW(h.fix(FallState{}), std::logic_error);
  EXPECT_THROW(h.get<TorsoState>(), std::logic_error);
  try {
    h.fix(SensorFrame{}).run();
    FAIL();
  } catch (const std::logic_error& e) {
    EXPECT_STREQ(e.what(), "CameraMatrixProvider requires TorsoState, not fixed");
  }
}

}  // namespace
}  // namespace nao
