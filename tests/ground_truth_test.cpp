// The simulator's ground truth of what a camera sees: lines, circle, intersections, balls, occlusion.
#include <gtest/gtest.h>

#include <cmath>

#include "controllers/StandController.h"
#include "robot/Paths.h"
#include "sim/GroundTruth.h"
#include "sim/World.h"

namespace nao::sim {
namespace {

SceneSpec scene(int robots) {
  SceneSpec spec;
  spec.field = FieldDimensions::load(dataPath("config/field_dimensions.json"));
  spec.robots.assign(robots, Eigen::Vector3d::Zero());
  spec.balls = {Eigen::Vector3d(0.3, 0.0, 0.05)};
  return spec;
}

JointArray lookingDown(double pitchDeg) {
  JointArray j = StandController::standPosture();
  j[HeadPitch] = pitchDeg * M_PI / 180;
  return j;
}

TEST(GroundTruth, CentreCircleHalfwayLineAndBallInView) {
  World world(scene(1), 1);
  world.placeRobot(0, Eigen::Vector3d(-1.2, 0, 0), lookingDown(15));
  const VisibleFeatures v = visibleFeatures(world, 0, CameraId::Top);
  bool halfway = false;
  for (const auto& l : v.lines) halfway = halfway || l.name == "halfway_line";
  EXPECT_TRUE(halfway);
  EXPECT_GT(v.centreCircleFractionVisible, 0.3);
  ASSERT_EQ(v.balls.size(), 1u);
  // 1.5 m ahead: the ball's image radius follows the pinhole model.
  const double f = 240 / std::tan(world.cameraFovY() / 2);
  EXPECT_NEAR(v.balls[0].radiusPx, f * 0.05 / 1.44, 2.5);
  EXPECT_NEAR(v.balls[0].image.x(), 320, 5);
  // Everything reported lies on the image.
  for (const auto& x : v.intersections) {
    EXPECT_GE(x.image.x(), 0);
    EXPECT_LT(x.image.y(), 480);
  }
}

TEST(GroundTruth, BehindTheCameraIsNotVisible) {
  World world(scene(1), 1);
  world.placeRobot(0, Eigen::Vector3d(1.2, 0, 0), lookingDown(15));  // facing away from the circle
  const VisibleFeatures v = visibleFeatures(world, 0, CameraId::Top);
  EXPECT_EQ(v.centreCircleFractionVisible, 0);
  EXPECT_TRUE(v.balls.empty());
}

TEST(GroundTruth, ARobotInFrontHidesTheBall) {
  World world(scene(2), 1);
  world.placeRobot(0, Eigen::Vector3d(-1.2, 0, 0), lookingDown(15));
  world.placeRobot(1, Eigen::Vector3d(-0.4, 0, M_PI), StandController::standPosture());
  const VisibleFeatures v = visibleFeatures(world, 0, CameraId::Top);
  EXPECT_TRUE(v.balls.empty());
  world.placeRobot(1, Eigen::Vector3d(-0.4, 1.5, M_PI), StandController::standPosture());
  EXPECT_EQ(visibleFeatures(world, 0, CameraId::Top).balls.size(), 1u);
}

TEST(GroundTruth, MaxDistanceLimitsWhatCounts) {
  World world(scene(1), 1);
  world.placeRobot(0, Eigen::Vector3d(-3.0, 0, 0), lookingDown(5));
  const VisibleFeatures near = visibleFeatures(world, 0, CameraId::Top, 2.0);
  const VisibleFeatures all = visibleFeatures(world, 0, CameraId::Top);
  EXPECT_LT(near.centreCircleFractionVisible, all.centreCircleFractionVisible + 1e-9);
  EXPECT_TRUE(near.balls.empty());  // 3.3 m away
  EXPECT_EQ(all.balls.size(), 1u);
}

}  // namespace
}  // namespace nao::sim
