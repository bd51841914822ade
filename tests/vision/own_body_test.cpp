// The robot's own body (perception/OwnBody.h): the capsules from the joint angles hide what
// the simulator's rays say is the robot, little of the ground beside it, and a real ball
// touching a foot is still a ball.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>

#include <mujoco/mujoco.h>

#include "controllers/StandController.h"
#include "perception/OwnBody.h"
#include "perception/vision/CameraPipeline.h"
#include "robot/ForwardKinematics.h"
#include "robot/Paths.h"
#include "robot/RobotDimensions.h"
#include "sim/CameraRenderer.h"
#include "sim/ImageIO.h"
#include "sim/Lighting.h"
#include "sim/World.h"

namespace nao {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

TEST(OwnBody, RaySegmentDistanceIsTheMinimumOverBoth) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  auto v = [&] { return Vector3d(u(rng), u(rng), u(rng)); };
  for (int trial = 0; trial < 300; ++trial) {
    const Vector3d o = v(), d = v(), a = v(), b = trial % 10 == 0 ? a : v();
    double brute = 1e9;
    for (int i = 0; i <= 400; ++i)
      for (int j = 0; j <= 400; ++j) {
        const Vector3d p = a + (i / 400.0) * (b - a), q = o + (j / 50.0) * d.normalized();  // up to 8 m
        brute = std::min(brute, (p - q).squaredNorm());
      }
    const double exact = raySegmentDistanceSquared(o, d, a, b);
    EXPECT_LE(exact, brute + 1e-9) << trial;
    EXPECT_NEAR(std::sqrt(exact), std::sqrt(brute), 0.015) << trial;
  }
  // Behind the ray's origin does not count.
  EXPECT_NEAR(raySegmentDistanceSquared(Vector3d::Zero(), Vector3d::UnitX(), Vector3d(-1, 0, 0), Vector3d(-1, 1, 0)),
              1.0, 1e-12);
}

struct Scene {
  sim::World world;
  sim::CameraRenderer renderer;
  sim::Lighting lighting = sim::Lighting::parse("default", dataPath("config/lighting.json"));
  explicit Scene(const sim::SceneSpec& spec) : world(spec, 3), renderer(world.model()) {}
};

sim::SceneSpec spec(bool ball) {
  sim::SceneSpec s;
  s.field = FieldDimensions::load(dataPath("config/field_dimensions.json"));
  s.robots = {Vector3d(-2.0, 1.5, 0)};
  if (ball) s.balls = {Vector3d(-1.0, 1.0, 0.05)};
  return s;
}

CameraMatrix cameraMatrix(const sim::World& world, CameraId camera) {
  const SensorFrame sensors = world.sensors(0);
  const sim::CameraResolution res = world.cameraResolution(camera);
  return computeCameraMatrix(sensors.joints.position, sensors.inertial.angle, camera, CameraCalibration{},
                             CameraIntrinsics::fromFovY(res.width, res.height, world.cameraFovY()));
}

OwnBody bodyOf(const sim::World& world) {
  const SensorFrame sensors = world.sensors(0);
  return ownBodyAt(sensors.joints.position, robotToTorso(sensors), OwnBodyParams{});
}

// How far along `dir` from `eye` the first geom the renderer draws lies (groups 0-2, at least
// the near clipping plane's 1 cm from the camera; infinity: none), and which.
double firstDrawnGeom(const mjModel* m, mjData* d, const Vector3d& eye, const Vector3d& dir, int* which = nullptr) {
  mjtByte groups[mjNGROUP] = {1, 1, 1, 0, 0, 0};
  const Vector3d unit = dir.normalized();
  double travelled = 0;
  for (int hop = 0; hop < 8; ++hop) {
    const Vector3d from = eye + travelled * unit;
    mjtNum pnt[3] = {from.x(), from.y(), from.z()}, vec[3] = {unit.x(), unit.y(), unit.z()};
    int geom = -1;
    const mjtNum hit = mj_ray(m, d, pnt, vec, groups, 1, -1, &geom);
    if (hit < 0 || geom < 0) return std::numeric_limits<double>::infinity();
    travelled += hit;
    if (travelled >= 0.01) {
      if (which) *which = geom;
      return travelled;
    }
    travelled += 1e-4;  // clipped: the renderer does not draw it
  }
  return std::numeric_limits<double>::infinity();
}

bool rayMeetsRobot(const mjModel* m, mjData* d, const Vector3d& eye, const Vector3d& dir) {
  int geom = -1;
  if (!std::isfinite(firstDrawnGeom(m, d, eye, dir, &geom))) return false;
  const char* body = mj_id2name(m, mjOBJ_BODY, m->geom_bodyid[geom]);
  return body && std::string(body).rfind("r0/", 0) == 0;
}

// Head looking down at the feet, the hands and beside them; arms as in a walk's swing.
TEST(OwnBody, HidesWhatTheSimulatorSaysIsTheRobotAndLittleElse) {
  Scene scene(spec(false));
  sim::World& world = scene.world;
  long balls = 0, ballsHidden = 0, ballsHiddenAtToes = 0, robot = 0, robotHidden = 0, ground = 0, groundHidden = 0;
  for (double yawDeg : {-100.0, -60.0, -30.0, 0.0, 30.0, 60.0, 100.0})
    for (double pitchDeg : {29.0, 15.0})
      for (double swing : {-0.3, 0.3}) {
        JointArray posture = StandController::standPosture();
        posture[HeadYaw] = yawDeg * dims::kDeg;
        posture[HeadPitch] = pitchDeg * dims::kDeg;
        posture[LShoulderPitch] += swing;
        posture[RShoulderPitch] -= swing;
        world.placeRobot(0, Vector3d(-2.0, 1.5, 0.3), posture);
        const Eigen::Isometry3d field = world.cameraPose(0, CameraId::Bottom);
        const CameraMatrix cm = cameraMatrix(world, CameraId::Bottom);
        const OwnBody body = bodyOf(world);
        const Eigen::Isometry3d robotInField = cm.fieldPose(world.robotPose(0)) * cm.pose.inverse();
        for (int y = 2; y < cm.intrinsics.height; y += 6)
          for (int x = 2; x < cm.intrinsics.width; x += 6) {
            const Vector2d px(x + 0.5, y + 0.5);
            // The simulator's truth from the true camera pose; the model's ray from its own.
            const Vector3d rayRobot = cm.pixelRay(px);
            const Vector3d rayField = robotInField.linear() * rayRobot * 5.0;
            const bool isRobot = rayMeetsRobot(world.model(), world.data(), field.translation(), rayField);
            const bool hidden = body.hides(cm, px);
            if (isRobot) {
              ++robot;
              robotHidden += hidden;
            } else {
              ++ground;
              groundHidden += hidden;
            }
          }
        // Balls the camera truly sees (the ray to their centre meets nothing of the robot):
        // few are hidden, none in front of the toes.
        for (double bx = -0.3; bx <= 0.8; bx += 0.02)
          for (double by = -0.6; by <= 0.6; by += 0.02) {
            const Vector3d centre(bx, by, 0.05);
            const auto px = cm.project(centre);
            if (!px || !cm.isOnImage(*px)) continue;
            const Vector3d centreField = robotInField * centre;
            const Vector3d toCentre = centreField - field.translation();
            if (firstDrawnGeom(world.model(), world.data(), field.translation(), toCentre) < toCentre.norm()) continue;
            ++balls;
            const bool hidden = body.hides(cm, *px);
            ballsHidden += hidden;
            if (hidden && bx >= 0.14) ++ballsHiddenAtToes;
          }
      }
  std::printf("visible balls %ld, hidden %ld, hidden in front of the toes %ld\n", balls, ballsHidden, ballsHiddenAtToes);
  std::printf("robot pixels %ld, hidden %.3f; ground pixels %ld, hidden %.4f\n", robot,
              double(robotHidden) / robot, ground, double(groundHidden) / ground);
  ASSERT_GT(robot, 2000);  // the views do show the body
  ASSERT_GT(balls, 3000);
  // Measured: robot 1.000, ground 0.070, balls 0.066 (the model's shoulders and arms are a real
  // NAO's, thicker than the simulated capsules), none in front of the toes.
  EXPECT_GE(double(robotHidden) / robot, 0.95);
  EXPECT_LE(double(groundHidden) / ground, 0.1);
  EXPECT_LE(double(ballsHidden) / balls, 0.08);
  EXPECT_EQ(ballsHiddenAtToes, 0);  // where a kick wants it
}

// A real ball touching a foot (in front of the toes, at the toes' outer corner) is still seen, with the
// body known, by the bottom camera looking at it.
TEST(OwnBody, ABallTouchingAFootIsStillTheBall) {
  Scene scene(spec(true));
  sim::World& world = scene.world;
  const Vector3d robotPose(-2.0, 1.5, 0.3);
  CameraPipeline pipeline(CameraId::Bottom, FieldDimensions::load(dataPath("config/field_dimensions.json")));
  for (const Vector2d& rel : {Vector2d(0.16, 0.05), Vector2d(0.16, -0.05), Vector2d(0.16, 0.12), Vector2d(0.16, -0.12)}) {
    JointArray posture = StandController::standPosture();
    posture[HeadYaw] = std::atan2(rel.y(), rel.x() + 0.05);
    // The pitch that puts the ball nearest the image's middle row.
    double bestRow = 1e9;
    JointArray best = posture;
    for (double pitch = -10; pitch <= 29; pitch += 1) {
      posture[HeadPitch] = pitch * dims::kDeg;
      world.placeRobot(0, robotPose, posture);
      const auto px = cameraMatrix(world, CameraId::Bottom).project(Vector3d(rel.x(), rel.y(), 0.05));
      if (px && std::abs(px->y() - 120) < bestRow) {
        bestRow = std::abs(px->y() - 120);
        best = posture;
      }
    }
    world.placeRobot(0, robotPose, best);
    const Vector2d field = Eigen::Rotation2Dd(robotPose.z()) * rel + robotPose.head<2>();
    world.placeBall(0, Vector3d(field.x(), field.y(), 0.05));
    const CameraMatrix cm = cameraMatrix(world, CameraId::Bottom);
    const sim::CameraResolution res = world.cameraResolution(CameraId::Bottom);
    const cv::Mat rgb = scene.renderer.renderRgb(world.model(), world.data(), world.cameraIndex(0, CameraId::Bottom),
                                                 res.width, res.height, scene.lighting);
    const OwnBody body = bodyOf(world);
    const CameraPercepts& p = pipeline.process(sim::cameraImageFromRgb(rgb, CameraId::Bottom), cm, body);
    ASSERT_TRUE(p.ball.seen) << rel.transpose();
    EXPECT_LT((p.ball.position - rel).norm(), 0.03) << rel.transpose() << " seen at " << p.ball.position.transpose();
    EXPECT_FALSE(body.hides(cm, p.ball.image));
  }
}

}  // namespace
}  // namespace nao
