// The simulator's ground truth of what a camera sees: lines, circle, intersections, balls, occlusion.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include <mujoco/mujoco.h>

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

// firstHit tries only the geoms near the segment: on rays from robot and camera heights to
// the ground, to the balls and across the field (through robots, goals, balls, paint), it
// finds what mj_ray over every geom finds wherever that lies on the segment.
TEST(GroundTruth, FirstHitIsMjRaysNearestHitOnTheSegment) {
  SceneSpec spec = scene(2);
  spec.balls.push_back(Eigen::Vector3d(3.5, 1.0, 0.05));
  World world(spec, 1);
  world.placeRobot(0, Eigen::Vector3d(-1.2, 0, 0), lookingDown(15));
  world.placeRobot(1, Eigen::Vector3d(1.0, 0.2, 3.0), lookingDown(10));
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> x(-5.5, 5.5), y(-3.5, 3.5), z(0.0, 0.7);
  int hits = 0, robotHits = 0, paintHits = 0, misses = 0;
  for (int k = 0; k < 4000; ++k) {
    const Eigen::Vector3d from(x(rng), y(rng), k % 2 ? 0.45 : z(rng));
    // A quarter of the rays end just below the ground (the paint's top lies 0.5 mm up), half of
    // those on the halfway line; a quarter on a ball, a quarter on a robot, a quarter anywhere.
    Eigen::Vector3d to(x(rng), y(rng), k % 4 == 0 ? z(rng) : -0.01);
    if (k % 8 == 2) to.x() = 0.04 * (x(rng) / 5.5) / 2;  // onto the halfway line's paint
    if (k % 4 == 1) to = world.ballPosition(k % 2) + Eigen::Vector3d(0, 0, 0.02);
    if (k % 4 == 3) to = Eigen::Vector3d(world.robotPose(k % 8 == 3).x(), world.robotPose(k % 8 == 3).y(), z(rng));
    const Eigen::Vector3d dir = to - from;
    const mjtNum pnt[3] = {from.x(), from.y(), from.z()}, vec[3] = {dir.x(), dir.y(), dir.z()};
    int geom = -1;
    const mjtNum hit = mj_ray(world.model(), world.data(), pnt, vec, nullptr, 1, -1, &geom);
    const auto h = firstHit(world, from, to);
    if (hit >= 0 && hit <= 1) {
      ASSERT_TRUE(h) << k;
      EXPECT_EQ(h->geom, geom) << k;
      EXPECT_NEAR(h->fraction, hit, 1e-12) << k;
      ++hits;
      const char* name = mj_id2name(world.model(), mjOBJ_GEOM, geom);
      const std::string n = name ? name : "";
      if (n.rfind("r0/", 0) == 0 || n.rfind("r1/", 0) == 0) ++robotHits;
      if (n.rfind("field/", 0) == 0 && n != "field/carpet") ++paintHits;
    } else {
      EXPECT_FALSE(h) << k << ": " << h->fraction;
      ++misses;
    }
  }
  // Enough of each kind that the comparison means something.
  EXPECT_GT(hits, 1000);
  EXPECT_GT(robotHits, 50);
  EXPECT_GT(paintHits, 50);
  EXPECT_GT(misses, 50);
  std::printf("%d hits (%d on robots, %d on the paint), %d misses\n", hits, robotHits, paintHits, misses);
}

}  // namespace
}  // namespace nao::sim
