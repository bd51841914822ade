// The ball detector on simulated images: balls at distances up to 5 m in both cameras and
// under every lighting preset of the sweep are found where the simulator put them; scenes
// without a ball give no percept. Truth is the simulator's ball position.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>

#include "controllers/StandController.h"
#include "perception/CameraModel.h"
#include "perception/Geometry.h"
#include "perception/vision/BallDetector.h"
#include "perception/vision/VisionPipeline.h"
#include "robot/Paths.h"
#include "sim/CameraRenderer.h"
#include "sim/GroundTruth.h"
#include "sim/Lighting.h"
#include "sim/World.h"

namespace nao {
namespace {

constexpr double kDeg = M_PI / 180;

class BallScene : public ::testing::Test {
 protected:
  void SetUp() override {
    sim::SceneSpec spec;
    spec.field = FieldDimensions::load(dataPath("config/field_dimensions.json"));
    spec.balls = {Eigen::Vector3d(1, 0, 0.05)};
    world_ = std::make_unique<sim::World>(spec, 1);
    renderer_ = std::make_unique<sim::CameraRenderer>(world_->model());
  }

  // Robot at `pose` with the head at (yaw, pitch) deg; the ball at `ball` (field, on the carpet).
  VisionResult look(const Eigen::Vector3d& pose, double yawDeg, double pitchDeg, const Eigen::Vector2d& ball,
                    CameraId camera, const std::string& preset = "default") {
    JointArray posture = StandController::standPosture();
    posture[HeadYaw] = yawDeg * kDeg;
    posture[HeadPitch] = pitchDeg * kDeg;
    world_->placeRobot(0, pose, posture);
    world_->placeBall(0, Eigen::Vector3d(ball.x(), ball.y(), 0.05));
    const sim::Lighting lighting = sim::Lighting::parse(preset, dataPath("config/lighting.json"));
    const sim::CameraResolution res = world_->cameraResolution(camera);
    const CameraImage img = renderer_->renderImage(world_->model(), world_->data(), world_->cameraIndex(0, camera),
                                                   res.width, res.height, lighting, camera, 0, rng_);
    const SensorFrame s = world_->sensors(0);
    cm_ = computeCameraMatrix(s.joints.position, s.inertial.angle, camera, CameraCalibration{},
                              CameraIntrinsics::fromFovY(res.width, res.height, world_->cameraFovY()));
    return runVision(img, cm_);
  }

  std::unique_ptr<sim::World> world_;
  std::unique_ptr<sim::CameraRenderer> renderer_;
  std::mt19937_64 rng_{5};
  CameraMatrix cm_;
};

TEST_F(BallScene, FoundAtEveryDistanceWithinFivePercent) {
  const Eigen::Vector3d pose(-2, 0.5, 0);
  for (double d : {0.3, 0.6, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0}) {
    SCOPED_TRACE(d);
    // Near balls are for the bottom camera, far ones for the top camera, head pitched to see them.
    const CameraId camera = d < 0.8 ? CameraId::Bottom : CameraId::Top;
    const double pitch = camera == CameraId::Bottom ? 5 : std::clamp(20 - 4 * d, 0.0, 20.0);
    const Eigen::Vector2d ball = pose.head<2>() + d * Eigen::Vector2d(std::cos(0.15), std::sin(0.15));
    const VisionResult r = look(pose, 8, pitch, ball, camera);
    ASSERT_TRUE(r.ball.seen);
    const Eigen::Vector2d seen = robotToField(r.ball.position, world_->robotPose(0));
    const double dist = (ball - world_->cameraPose(0, camera).translation().head<2>()).norm();
    EXPECT_LT((seen - ball).norm(), 0.05 * dist) << seen.transpose() << " vs " << ball.transpose();
    // The covariance is a real one and covers the error.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(r.ball.covariance);
    EXPECT_GT(es.eigenvalues().minCoeff(), 0);
    EXPECT_LT((seen - ball).norm(), 5 * std::sqrt(es.eigenvalues().maxCoeff()) + 0.02);
    // The image radius agrees with the truth.
    const auto truth = sim::visibleFeatures(*world_, 0, camera, 10);
    ASSERT_EQ(truth.balls.size(), 1u);
    EXPECT_NEAR(r.ball.radiusPx, truth.balls[0].radiusPx, 0.25 * truth.balls[0].radiusPx + 1);
    EXPECT_NEAR(vision::expectedBallRadius(cm_, truth.balls[0].image, 0.05), truth.balls[0].radiusPx,
                0.05 * truth.balls[0].radiusPx + 0.3);
  }
}

TEST_F(BallScene, FoundUnderEveryLightingPreset) {
  const Eigen::Vector3d pose(1, -1, 90 * kDeg);
  const Eigen::Vector2d ball(1.3, 1.0);
  for (const auto& l : sim::Lighting::sweep(dataPath("config/lighting.json"))) {
    SCOPED_TRACE(l.name);
    const VisionResult r = look(pose, -5, 12, ball, CameraId::Top, l.name);
    ASSERT_TRUE(r.ball.seen);
    EXPECT_LT((robotToField(r.ball.position, world_->robotPose(0)) - ball).norm(), 0.1);
  }
}

TEST_F(BallScene, NoBallNoPercept) {
  // The ball far away behind the robot; the views show lines, the circle, goals, the wall.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  int percepts = 0;
  for (int i = 0; i < 24; ++i) {
    const Eigen::Vector3d pose(-4 + 8 * u(rng), -2.5 + 5 * u(rng), (u(rng) - 0.5) * 2 * M_PI);
    const Eigen::Vector2d behind = pose.head<2>() - 0.4 * Eigen::Vector2d(std::cos(pose.z()), std::sin(pose.z()));
    const CameraId camera = i % 2 ? CameraId::Top : CameraId::Bottom;
    const VisionResult r = look(pose, 0, camera == CameraId::Top ? 10 : 0, behind, camera);
    percepts += r.ball.seen;
  }
  EXPECT_EQ(percepts, 0);
}

}  // namespace
}  // namespace nao
