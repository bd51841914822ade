// Where the auto exposure meters (perception/ExposureWeighting.h, AutoExposureWeighting): judged
// by geometry the test computes itself -- which cells' pixels see the ground near the robot --
// and, through the simulator's camera model, by what the metering does to a scene whose hall is
// lit and whose field is dark.
#include <gtest/gtest.h>

#include <cmath>

#include "controllers/StandController.h"
#include "controllers/modules/AutoExposureWeighting.h"
#include "perception/CameraCalibration.h"
#include "perception/CameraModel.h"
#include "perception/ExposureWeighting.h"
#include "perception/OwnBody.h"
#include "robot/Blackboard.h"
#include "robot/ForwardKinematics.h"
#include "sim/CameraSensor.h"

namespace nao {
namespace {

constexpr double kDeg = M_PI / 180;

struct View {
  JointArray joints;
  Eigen::Isometry3d torso;
  CameraMatrix cm;
};

View standing(CameraId camera, double headYawDeg, double headPitchDeg) {
  View v;
  v.joints = StandController::standPosture();
  v.joints[HeadYaw] = headYawDeg * kDeg;
  v.joints[HeadPitch] = headPitchDeg * kDeg;
  v.torso = robotToTorso(v.joints, 0, 0);
  const CameraIntrinsics in =
      camera == CameraId::Top ? CameraIntrinsics::fromFovY(640, 480) : CameraIntrinsics::fromFovY(320, 240);
  v.cm = computeCameraMatrix(v.joints, v.torso, camera, CameraCalibration{}, in);
  return v;
}

// The share of a cell's area whose rays meet the ground within `range` of the camera's foot,
// counted on a fine grid of its own.
double groundShare(const CameraMatrix& cm, int row, int col, double range) {
  const double w = cm.intrinsics.width / 4.0, h = cm.intrinsics.height / 4.0;
  int n = 0, ground = 0;
  for (double y = row * h + 0.25; y < (row + 1) * h; y += 2)
    for (double x = col * w + 0.25; x < (col + 1) * w; x += 2) {
      ++n;
      const auto g = cm.pixelToGround(Eigen::Vector2d(x, y));
      ground += g && (*g - cm.pose.translation().head<2>()).norm() <= range;
    }
  return static_cast<double>(ground) / n;
}

TEST(ExposureWeighting, LookingAheadMetersTheNearGroundNotTheHall) {
  const View v = standing(CameraId::Top, 0, 0);
  const ExposureWeightingParams p;  // 6 m
  const ExposureWeights w = exposureWeights(v.cm, OwnBody{}, p);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      const double share = groundShare(v.cm, r, c, p.maxDistance);
      EXPECT_NEAR(w.at(r, c), 15 * share, 2.0) << "cell " << r << "," << c << " sees " << share << " near ground";
    }
  // Looking ahead, the upper half of the image is the hall and the far field.
  EXPECT_EQ(w.at(0, 0), 0);
  EXPECT_EQ(w.at(0, 3), 0);
  EXPECT_EQ(w.at(3, 1), 15);
  EXPECT_FALSE(w.uniform());
}

TEST(ExposureWeighting, TheOwnBodyIsNotMetered) {
  // The bottom camera looking down between the feet sees the feet and shins in its lower cells.
  const View v = standing(CameraId::Bottom, 0, 25);
  const OwnBody body = ownBodyAt(v.joints, v.torso, OwnBodyParams{});
  const ExposureWeights without = exposureWeights(v.cm, OwnBody{}, {});
  const ExposureWeights with = exposureWeights(v.cm, body, {});
  int hiddenCells = 0, lowered = 0;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      EXPECT_EQ(without.at(r, c), 15) << "looking down, every cell sees the near ground";
      EXPECT_LE(with.at(r, c), without.at(r, c));
      int hidden = 0, n = 0;
      for (double y = r * 60 + 1; y < (r + 1) * 60; y += 3)
        for (double x = c * 80 + 1; x < (c + 1) * 80; x += 3, ++n) hidden += body.hides(v.cm, Eigen::Vector2d(x, y));
      if (hidden > n / 3) {
        ++hiddenCells;
        lowered += with.at(r, c) <= 10;
      }
    }
  ASSERT_GT(hiddenCells, 0) << "the test's view should show the feet";
  EXPECT_EQ(lowered, hiddenCells);
}

TEST(ExposureWeighting, WithoutNearGroundInViewTheCameraKeepsItsDefault) {
  View v = standing(CameraId::Top, 0, -38);  // the head up: the hall only
  EXPECT_TRUE(exposureWeights(v.cm, OwnBody{}, {}).uniform());
  ExposureWeightingParams off;
  off.enabled = false;
  const View ahead = standing(CameraId::Top, 0, 0);
  EXPECT_TRUE(exposureWeights(ahead.cm, OwnBody{}, off).uniform());
  // Nearer ground only: fewer cells count.
  ExposureWeightingParams near;
  near.maxDistance = 1.5;
  const ExposureWeights n = exposureWeights(ahead.cm, OwnBody{}, near), f = exposureWeights(ahead.cm, OwnBody{}, {});
  int sumNear = 0, sumFar = 0;
  for (int k = 0; k < 16; ++k) sumNear += n.cell[k], sumFar += f.cell[k];
  EXPECT_LT(sumNear, sumFar);
}

// The camera model meters with the weights: a scene whose upper half (the lit hall) is bright and
// whose lower half (the field) is dark is exposed brighter when only the lower cells count, and
// the default weights meter the image's plain mean as before.
TEST(ExposureWeighting, TheCameraModelExposesForTheWeightedCells) {
  cv::Mat rgb(480, 640, CV_8UC3);
  rgb.rowRange(0, 240).setTo(cv::Scalar(200, 200, 200));
  rgb.rowRange(240, 480).setTo(cv::Scalar(20, 60, 20));
  sim::CameraSensorParams p;
  p.vignetting = false;
  auto settledBrightness = [&](const ExposureWeights& w) {
    sim::CameraSensor sensor;
    sensor.setMeteringWeights(w);
    sensor.settle(rgb, Eigen::Vector3d::Ones(), p, CameraId::Top);
    return sensor.lightGains(p)[1];
  };
  ExposureWeights field;
  field.cell.fill(0);
  for (int k = 8; k < 16; ++k) field.cell[static_cast<std::size_t>(k)] = 15;
  const double whole = settledBrightness(ExposureWeights{}), onField = settledBrightness(field);
  // Metered mean Y: whole image (200 + 47) / 2 = 123.5 at gain 1; the field alone 47.
  EXPECT_LT(whole, 1.0);
  EXPECT_GT(onField, 1.5);
  EXPECT_NEAR(onField / whole, 123.5 / 47.1, 0.35);
  // The weights scale, they do not count: all cells at 1 meter like all at 15.
  ExposureWeights ones;
  ones.cell.fill(1);
  EXPECT_DOUBLE_EQ(settledBrightness(ones), whole);
}

// The module: a camera keeps the default until its camera matrix is known, takes the view's
// weights for its own camera only, and keeps them through small changes (a scanning head
// would otherwise change them with nearly every image; on a NAO each change is a USB transfer).
TEST(ExposureWeighting, TheModuleFollowsItsCameraWithHysteresis) {
  Pipeline p;
  p.add(std::make_unique<modules::AutoExposureWeighting>());
  p.inputs<CurrentImage, ImageCameraMatrix, OwnBody>();
  p.sort();
  Blackboard board;
  CameraImage& image = board.write<CurrentImage>().image;
  image.camera = CameraId::Top;
  image.width = 640;
  image.height = 480;
  image.yuyv.assign(640 * 480 * 2, 128);
  board.write<OwnBody>() = OwnBody{};
  ImageCameraMatrix& cm = board.write<ImageCameraMatrix>();
  cm.camera = CameraId::Top;
  cm.matrix = standing(CameraId::Top, 0, 0).cm;
  p.update(board);  // no motion cycle seen yet: the default
  EXPECT_TRUE(board.read<AutoExposureWeights>().camera[0].uniform());
  cm.valid = true;
  p.update(board);
  const ExposureWeights ahead = exposureWeights(cm.matrix, OwnBody{}, {});
  EXPECT_EQ(board.read<AutoExposureWeights>().camera[0], ahead);
  EXPECT_TRUE(board.read<AutoExposureWeights>().camera[1].uniform()) << "the bottom camera's own images decide its";
  // A degree down changes a few cells a little: kept. Ten degrees: taken.
  cm.matrix = standing(CameraId::Top, 0, 1).cm;
  const ExposureWeights slightly = exposureWeights(cm.matrix, OwnBody{}, {});
  int change = 0;
  for (int k = 0; k < 16; ++k) change += std::abs(slightly.cell[k] - ahead.cell[k]);
  ASSERT_GT(change, 0);
  ASSERT_LT(change, ExposureWeightingParams{}.minChange);
  p.update(board);
  EXPECT_EQ(board.read<AutoExposureWeights>().camera[0], ahead);
  cm.matrix = standing(CameraId::Top, 0, 10).cm;
  p.update(board);
  EXPECT_EQ(board.read<AutoExposureWeights>().camera[0], exposureWeights(cm.matrix, OwnBody{}, {}));
  EXPECT_NE(board.read<AutoExposureWeights>().camera[0], ahead);
}

}  // namespace
}  // namespace nao
