// The camera model: intrinsics, projection and back-projection, the horizon, calibration
// offsets and the field-frame helpers, against hand-computed geometry.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <random>

#include "perception/CameraModel.h"
#include "perception/Geometry.h"
#include "robot/Error.h"

namespace nao {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

// A camera at height h above the robot origin, pitched down by a (Ry(a)), rolled by r about its axis.
CameraMatrix cameraAt(double h, double a, double r = 0, double yaw = 0) {
  CameraMatrix m;
  m.pose.translation() = Eigen::Vector3d(0.05, 0.01, h);
  m.pose.linear() = rotZ(yaw) * rotY(a) * rotX(r);
  m.intrinsics = CameraIntrinsics::fromFovY(640, 480);
  return m;
}

JointArray zeros() {
  JointArray j{};
  j.fill(0);
  return j;
}

TEST(CameraIntrinsics, FromFovY) {
  const auto k = CameraIntrinsics::fromFovY(640, 480, 43.7 * kDeg);
  EXPECT_NEAR(k.fy, 240 / std::tan(21.85 * kDeg), 1e-9);
  EXPECT_NEAR(k.fy, 598.53, 0.01);
  EXPECT_DOUBLE_EQ(k.fx, k.fy);
  EXPECT_DOUBLE_EQ(k.cx, 320);
  EXPECT_DOUBLE_EQ(k.cy, 240);
  EXPECT_NEAR(k.fovX() / kDeg, 56.27, 0.01);
  EXPECT_NEAR(k.fovY() / kDeg, 43.7, 1e-9);
  const auto b = CameraIntrinsics::nominal(CameraId::Bottom);
  EXPECT_EQ(b.width, 320);
  EXPECT_EQ(b.height, 240);
  EXPECT_NEAR(b.fy, 120 / std::tan(21.85 * kDeg), 1e-9);
  const CameraIntrinsics def;
  EXPECT_NEAR(def.fx, k.fx, 1e-12);
  EXPECT_EQ(def.width, 640);
  EXPECT_THROW(CameraIntrinsics::fromFovY(0, 480), Error);
  EXPECT_THROW(CameraIntrinsics::fromFovY(640, 480, 0), Error);
}

TEST(CameraMatrix, OpticalAxisMapsToImageCentre) {
  const auto m = cameraAt(0.5, 0.3, 0.1, 0.2);
  for (double d : {0.2, 1.0, 7.0}) {
    const Eigen::Vector3d p = m.pose * Eigen::Vector3d(d, 0, 0);
    const auto px = m.project(p);
    ASSERT_TRUE(px);
    EXPECT_NEAR(px->x(), 320, 1e-9);
    EXPECT_NEAR(px->y(), 240, 1e-9);
  }
}

TEST(CameraMatrix, ProjectionAxes) {
  const auto m = cameraAt(0.5, 0);  // level camera
  const auto left = m.project(Eigen::Vector3d(2, 1, 0.5));
  const auto up = m.project(Eigen::Vector3d(2, 0.01, 1.0));
  ASSERT_TRUE(left && up);
  EXPECT_LT(left->x(), 320);  // left in the world = left in the image
  EXPECT_NEAR(left->x(), 320 - m.intrinsics.fx * (1 - 0.01) / (2 - 0.05), 1e-9);
  EXPECT_LT(up->y(), 240);  // up in the world = up in the image (row 0 at the top)
  EXPECT_NEAR(up->y(), 240 - m.intrinsics.fy * 0.5 / 1.95, 1e-9);
  EXPECT_FALSE(m.project(Eigen::Vector3d(-1, 0, 0.5)));   // behind
  EXPECT_FALSE(m.project(Eigen::Vector3d(0.05, 0.3, 0)));  // in the camera plane
}

TEST(CameraMatrix, CentreGroundPointFromPitch) {
  const double h = 0.5, a = 30 * kDeg;
  const auto m = cameraAt(h, a);
  const auto g = m.pixelToGround({320, 240});
  ASSERT_TRUE(g);
  EXPECT_NEAR(g->x(), 0.05 + h / std::tan(a), 1e-9);
  EXPECT_NEAR(g->y(), 0.01, 1e-9);
  // The bottom row centre sees closer: the ray is 21.85 deg steeper.
  const auto gb = m.pixelToGround({320, 480});
  ASSERT_TRUE(gb);
  EXPECT_NEAR(gb->x(), 0.05 + h / std::tan(a + 21.85 * kDeg), 1e-9);
  // Above a plane at height z the same ray meets it further in.
  const auto gz = m.pixelToGround({320, 240}, 0.05);
  ASSERT_TRUE(gz);
  EXPECT_NEAR(gz->x(), 0.05 + (h - 0.05) / std::tan(a), 1e-9);
}

TEST(CameraMatrix, RoundTrips) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 640), v(0, 480), ang(-0.3, 0.3);
  for (int c = 0; c < 20; ++c) {
    const auto m = cameraAt(0.3 + 0.02 * c, 0.35 + ang(rng), ang(rng), ang(rng));
    for (int i = 0; i < 200; ++i) {
      const Eigen::Vector2d px(u(rng), v(rng));
      const auto g = m.pixelToGround(px);
      if (m.isAboveHorizon(px)) {
        EXPECT_FALSE(g);
        continue;
      }
      ASSERT_TRUE(g);
      const auto back = m.projectGround(*g);
      ASSERT_TRUE(back);
      EXPECT_NEAR((*back - px).norm(), 0, 1e-7);
      // 3-D points along the ray project to the same pixel.
      const Eigen::Vector3d p = m.pose.translation() + 0.7 * m.pixelRay(px);
      EXPECT_NEAR((*m.project(p) - px).norm(), 0, 1e-9);
    }
  }
}

TEST(CameraMatrix, AboveHorizonHasNoGroundPoint) {
  const auto m = cameraAt(0.5, 5 * kDeg);
  EXPECT_FALSE(m.pixelToGround({320, 0}));
  EXPECT_TRUE(m.pixelToGround({320, 479}));
  // A camera below the plane sees it above the horizon.
  EXPECT_TRUE(m.pixelToGround({320, 0}, 1.0));
  EXPECT_FALSE(m.pixelToGround({320, 479}, 1.0));
}

TEST(CameraMatrix, Horizon) {
  // Level camera: the horizon is the middle row.
  auto m = cameraAt(0.5, 0);
  EXPECT_NEAR(*m.horizonY(0), 240, 1e-9);
  EXPECT_NEAR(*m.horizonY(640), 240, 1e-9);
  // Pitched down by a: the horizon moves up by f tan(a).
  const double a = 10 * kDeg;
  m = cameraAt(0.5, a);
  EXPECT_NEAR(*m.horizonY(320), 240 - m.intrinsics.fy * std::tan(a), 1e-9);
  EXPECT_TRUE(m.isAboveHorizon({320, 240 - m.intrinsics.fy * std::tan(a) - 1}));
  EXPECT_FALSE(m.isAboveHorizon({320, 240 - m.intrinsics.fy * std::tan(a) + 1}));
  // Rolled: the horizon tilts by the roll; its points' rays are level.
  const double r = 8 * kDeg;
  m = cameraAt(0.5, a, r);
  const auto line = m.horizon();
  ASSERT_TRUE(line);
  EXPECT_DOUBLE_EQ(line->from.x(), 0);
  EXPECT_DOUBLE_EQ(line->to.x(), 640);
  // Rolling about the optical axis turns the image rigidly about the principal point.
  EXPECT_NEAR(std::abs(std::atan2(line->to.y() - line->from.y(), 640)), r, 1e-9);
  for (const auto& p : {line->from, line->to, Eigen::Vector2d((line->from + line->to) / 2)})
    EXPECT_NEAR(m.pixelRay(p).z(), 0, 1e-12);
  // Rolled 90 deg: vertical horizon, spanning the image's height.
  m = cameraAt(0.5, 0, std::numbers::pi / 2);
  EXPECT_FALSE(m.horizonY(10));
  const auto vertical = m.horizon();
  ASSERT_TRUE(vertical);
  EXPECT_NEAR(vertical->from.x(), 320, 1e-9);
  EXPECT_NEAR(vertical->to.x(), 320, 1e-9);
  // Straight down: no horizon.
  m = cameraAt(0.5, std::numbers::pi / 2);
  EXPECT_FALSE(m.horizon());
}

TEST(CameraMatrix, IsOnImage) {
  const auto m = cameraAt(0.5, 0);
  EXPECT_TRUE(m.isOnImage({0, 0}));
  EXPECT_TRUE(m.isOnImage({639.5, 479.5}));
  EXPECT_FALSE(m.isOnImage({640, 10}));
  EXPECT_FALSE(m.isOnImage({10, -0.01}));
}

TEST(ComputeCameraMatrix, UprightStandingTopCamera) {
  const JointArray j = zeros();
  const auto intr = CameraIntrinsics::nominal(CameraId::Top);
  const auto m = computeCameraMatrix(j, Eigen::Vector2d(0, 0), CameraId::Top, CameraCalibration{}, intr);
  const Eigen::Vector3d expected(0.05871, 0, 0.24809 + 0.2115 + 0.06364);
  EXPECT_NEAR((m.pose.translation() - expected).norm(), 0, 1e-12);
  EXPECT_TRUE(m.pose.linear().isApprox(rotY(1.2 * kDeg), 1e-12));
  EXPECT_EQ(m.intrinsics.width, 640);
  // The image centre sees the ground h / tan(1.2 deg) ahead.
  const auto g = m.pixelToGround({320, 240});
  ASSERT_TRUE(g);
  EXPECT_NEAR(g->x(), 0.05871 + expected.z() / std::tan(1.2 * kDeg), 1e-6);
}

TEST(ComputeCameraMatrix, ImuOverloadMatchesExplicitTorsoPose) {
  JointArray j = zeros();
  j[HeadYaw] = 0.3;
  j[HeadPitch] = 0.2;
  j[LHipPitch] = j[RHipPitch] = -0.4;
  j[LKneePitch] = j[RKneePitch] = 0.8;
  j[LAnklePitch] = j[RAnklePitch] = -0.4;
  const CameraCalibration calib{0.01, -0.02, 0.03, 0.01, -0.015, 0.02};
  const auto intr = CameraIntrinsics::nominal(CameraId::Bottom);
  const double roll = 0.03, pitch = 0.05;
  const auto a = computeCameraMatrix(j, Eigen::Vector2d(roll, pitch), CameraId::Bottom, calib, intr);
  const auto b = computeCameraMatrix(j, robotToTorso(j, roll, pitch), CameraId::Bottom, calib, intr);
  EXPECT_TRUE(a.pose.isApprox(b.pose, 1e-12));
  EXPECT_NEAR(a.pose.translation().z(),
              torsoHeightAboveGround(j, roll, pitch) +
                  (torsoTilt(roll, pitch) * torsoToCalibratedCamera(j, CameraId::Bottom, calib).translation()).z(),
              1e-12);
}

// The explicit-torso-pose camera matrix with the head pitched by p (straight legs, torso at 0.3 m).
CameraMatrix pitchedHead(CameraId cam, double headPitch, const CameraCalibration& calib) {
  JointArray j = zeros();
  j[HeadPitch] = headPitch;
  Eigen::Isometry3d torso = Eigen::Isometry3d::Identity();
  torso.translation() = Eigen::Vector3d(0, 0, 0.3);
  return computeCameraMatrix(j, torso, cam, calib, CameraIntrinsics::nominal(cam));
}

double centreGroundDistance(const CameraMatrix& m) {
  return m.pixelToGround({m.intrinsics.cx, m.intrinsics.cy})->x();
}

TEST(ComputeCameraMatrix, CameraPitchOffsetTiltsTheOpticalAxis) {
  const double p = 0.35, d = 2 * kDeg;
  for (CameraId cam : {CameraId::Top, CameraId::Bottom}) {
    const bool top = cam == CameraId::Top;
    const double mount = top ? 1.2 * kDeg : 39.7 * kDeg;
    const Eigen::Vector3d offset = top ? Eigen::Vector3d(0.05871, 0, 0.06364) : Eigen::Vector3d(0.05071, 0, 0.01774);
    const Eigen::Vector3d c = Eigen::Vector3d(0, 0, 0.3 + 0.2115) + rotY(p) * offset;
    CameraCalibration calib;
    (top ? calib.topPitch : calib.bottomPitch) = d;
    // The camera offset turns the optical axis about the optical centre: total pitch p + mount + d.
    EXPECT_NEAR(centreGroundDistance(pitchedHead(cam, p, {})), c.x() + c.z() / std::tan(p + mount), 1e-9);
    EXPECT_NEAR(centreGroundDistance(pitchedHead(cam, p, calib)), c.x() + c.z() / std::tan(p + mount + d), 1e-9);
    // The other camera's offset does nothing here.
    CameraCalibration other;
    (top ? other.bottomPitch : other.topPitch) = d;
    EXPECT_TRUE(pitchedHead(cam, p, other).pose.isApprox(pitchedHead(cam, p, {}).pose, 1e-15));
  }
}

TEST(ComputeCameraMatrix, BodyPitchOffsetRotatesAboutTheTorso) {
  const double p = 0.35, d = -1.5 * kDeg;
  CameraCalibration calib;
  calib.bodyPitch = d;
  // The whole head chain turns about the torso origin: camera at Ry(d) of its nominal place.
  const Eigen::Vector3d c =
      Eigen::Vector3d(0, 0, 0.3) + rotY(d) * (Eigen::Vector3d(0, 0, 0.2115) + rotY(p) * Eigen::Vector3d(0.05871, 0, 0.06364));
  const auto m = pitchedHead(CameraId::Top, p, calib);
  EXPECT_NEAR((m.pose.translation() - c).norm(), 0, 1e-12);
  EXPECT_NEAR(centreGroundDistance(m), c.x() + c.z() / std::tan(p + 1.2 * kDeg + d), 1e-9);
  // A body pitch equals the same torso pitch (same rotation, same pivot).
  Eigen::Isometry3d torso = Eigen::Isometry3d::Identity();
  torso.translation() = Eigen::Vector3d(0, 0, 0.3);
  torso.linear() = rotY(d);
  JointArray j = zeros();
  j[HeadPitch] = p;
  const auto viaTorso = computeCameraMatrix(j, torso, CameraId::Top, {}, CameraIntrinsics::nominal(CameraId::Top));
  EXPECT_TRUE(viaTorso.pose.isApprox(m.pose, 1e-12));
}

TEST(ComputeCameraMatrix, CameraRollRotatesTheImageAboutTheCentre) {
  const double p = 0.5, r = 3 * kDeg;
  CameraCalibration calib;
  calib.bottomRoll = r;
  const auto m0 = pitchedHead(CameraId::Bottom, p, {});
  const auto m1 = pitchedHead(CameraId::Bottom, p, calib);
  EXPECT_TRUE(m0.pose.translation().isApprox(m1.pose.translation(), 1e-15));
  const Eigen::Vector2d centre(160, 120);
  for (const Eigen::Vector3d& q : {Eigen::Vector3d(0.6, 0.1, 0), Eigen::Vector3d(0.4, -0.15, 0), Eigen::Vector3d(0.5, 0, 0)}) {
    const Eigen::Vector2d a = *m0.project(q) - centre, b = *m1.project(q) - centre;
    EXPECT_NEAR(a.norm(), b.norm(), 1e-9);
    // Rx(r) in the camera frame: camera coordinates become Rx(-r) p, which turns the offset
    // from the principal point by -r in (u, v).
    if (a.norm() > 1) {
      EXPECT_NEAR(std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b)), -r, 1e-9);
    }
  }
}

TEST(ComputeCameraMatrix, RollWithPitchOrder) {
  // C_cam = Rx(roll) Ry(pitch): roll first (outer), then pitch in the rolled frame.
  CameraCalibration calib;
  calib.topRoll = 0.05;
  calib.topPitch = 0.04;
  const JointArray j = zeros();
  const auto t = torsoToCalibratedCamera(j, CameraId::Top, calib);
  const Eigen::Matrix3d expected = rotY(1.2 * kDeg) * rotX(0.05) * rotY(0.04);
  EXPECT_TRUE(t.linear().isApprox(expected, 1e-12));
  calib = {};
  calib.bodyRoll = 0.02;
  calib.bodyPitch = -0.03;
  const auto tb = torsoToCalibratedCamera(j, CameraId::Top, calib);
  EXPECT_TRUE(tb.linear().isApprox(rotX(0.02) * rotY(-0.03) * rotY(1.2 * kDeg), 1e-12));
  EXPECT_TRUE(tb.translation().isApprox(rotX(0.02) * rotY(-0.03) * Eigen::Vector3d(0.05871, 0, 0.2115 + 0.06364), 1e-12));
}

TEST(FieldHelpers, PoseTransforms) {
  const Eigen::Vector3d pose(1.0, -2.0, 0.7);
  const Eigen::Vector2d p(3.0, 0.5);
  EXPECT_NEAR((robotToField(fieldToRobot(p, pose), pose) - p).norm(), 0, 1e-12);
  const Eigen::Vector2d r = fieldToRobot(Eigen::Vector2d(1.0 + std::cos(0.7), -2.0 + std::sin(0.7)), pose);
  EXPECT_NEAR((r - Eigen::Vector2d(1, 0)).norm(), 0, 1e-12);
  EXPECT_NEAR(normalizeAngle(3 * std::numbers::pi), std::numbers::pi, 1e-12);
  EXPECT_NEAR(normalizeAngle(-0.5), -0.5, 1e-15);
}

TEST(FieldHelpers, FieldToImageRoundTrip) {
  JointArray j = zeros();
  j[HeadPitch] = 0.3;
  j[HeadYaw] = -0.2;
  const auto m = computeCameraMatrix(j, Eigen::Vector2d(0.01, 0.02), CameraId::Top, {},
                                     CameraIntrinsics::nominal(CameraId::Top));
  const Eigen::Vector3d pose(-1.5, 0.8, 2.5);
  // A point 1.5 m in front of the robot, on the ground, in the field frame.
  const Eigen::Vector2d ahead = robotToField(Eigen::Vector2d(1.5, -0.3), pose);
  const auto px = m.fieldToImage(ahead, pose);
  ASSERT_TRUE(px);
  EXPECT_NEAR((*px - *m.projectGround(Eigen::Vector2d(1.5, -0.3))).norm(), 0, 1e-9);
  const auto back = m.imageToField(*px, pose);
  ASSERT_TRUE(back);
  EXPECT_NEAR((*back - ahead).norm(), 0, 1e-9);
  // A ball centre (z = 0.05) back-projected onto its own height.
  const Eigen::Vector3d ball(ahead.x(), ahead.y(), 0.05);
  const auto bpx = m.fieldToImage(ball, pose);
  ASSERT_TRUE(bpx);
  EXPECT_NEAR((*m.imageToField(*bpx, pose, 0.05) - ahead).norm(), 0, 1e-9);
  // The field-frame camera pose agrees with the robot-frame one.
  const Eigen::Isometry3d fc = m.fieldPose(pose);
  const Eigen::Vector3d camInCam = fc.inverse() * Eigen::Vector3d(ahead.x(), ahead.y(), 0);
  EXPECT_NEAR(px->x(), 320 - m.intrinsics.fx * camInCam.y() / camInCam.x(), 1e-9);
}

TEST(CameraMatrix, ProjectionSpeed) {
  const auto m = cameraAt(0.5, 0.4, 0.02, 0.1);
  const int n = 1'000'000;
  double sum = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < n; ++i) {
    const auto px = m.project(Eigen::Vector3d(1.0 + 1e-6 * i, 0.2, 0));
    if (px) sum += px->x();
  }
  const auto t1 = std::chrono::steady_clock::now();
  for (int i = 0; i < n; ++i) {
    const auto g = m.pixelToGround(Eigen::Vector2d(100 + 1e-4 * i, 400));
    if (g) sum += g->x();
  }
  const auto t2 = std::chrono::steady_clock::now();
  const double projectNs = std::chrono::duration<double, std::nano>(t1 - t0).count() / n;
  const double groundNs = std::chrono::duration<double, std::nano>(t2 - t1).count() / n;
  std::printf("project: %.1f ns/point, pixelToGround: %.1f ns/pixel (checksum %.1f)\n", projectNs, groundNs, sum);
  EXPECT_GT(sum, 0);
}

}  // namespace
}  // namespace nao
