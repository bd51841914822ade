// The simulated world: servo model, placement, balls, pushes, injected miscalibration,
// NaN detection, SimBackend's camera timing.
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include "robot/Error.h"
#include "sim/SceneBuilder.h"
#include "sim/ServoModel.h"
#include "sim/SimBackend.h"
#include "sim/Turf.h"
#include "sim/World.h"

namespace nao::sim {
namespace {

SceneSpec robotScene() {
  SceneSpec spec;
  spec.robots = {Eigen::Vector3d(1.0, -0.5, 0.3)};
  return spec;
}

SceneSpec ballScene() {
  SceneSpec spec;
  spec.robots = {Eigen::Vector3d(-3.5, 2.5, 0.0)};  // out of the ball's way
  spec.balls = {Eigen::Vector3d(0, 0, 0.05)};
  return spec;
}

// A standing posture (knees bent, arms down); the controllers' one is tested in stand_test.
JointArray posture() {
  JointArray p{};
  p[LHipPitch] = p[RHipPitch] = -0.45;
  p[LKneePitch] = p[RKneePitch] = 0.9;
  p[LAnklePitch] = p[RAnklePitch] = -0.45;
  p[LShoulderPitch] = p[RShoulderPitch] = 1.57;
  p[LShoulderRoll] = 0.1;
  p[RShoulderRoll] = -0.1;
  p[LElbowRoll] = -0.05;
  p[RElbowRoll] = 0.05;
  return p;
}

Eigen::Matrix3d rx(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).toRotationMatrix(); }
Eigen::Matrix3d ry(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix(); }

TEST(ServoModel, TorqueSpeedLine) {
  const ServoParams p = ServoModel::defaults(LKneePitch, 8.0);
  EXPECT_NEAR(p.noLoadSpeed, 6.4, 0.01);
  EXPECT_DOUBLE_EQ(ServoModel::torqueLimit(p, 0.0, 1.0), 8.0);
  EXPECT_NEAR(ServoModel::torqueLimit(p, p.noLoadSpeed / 2, 1.0), 4.0, 1e-12);
  EXPECT_DOUBLE_EQ(ServoModel::torqueLimit(p, p.noLoadSpeed / 2, -1.0), 8.0);  // braking
  EXPECT_DOUBLE_EQ(ServoModel::torqueLimit(p, 2 * p.noLoadSpeed, 1.0), 0.0);
  // Saturates at stall; scales with stiffness; stiffness 0 is off.
  EXPECT_DOUBLE_EQ(ServoModel::torque(p, 1.0, 0.0, 0.0, 1.0), 8.0);
  EXPECT_DOUBLE_EQ(ServoModel::torque(p, -1.0, 0.0, 0.0, 0.5), -4.0);
  EXPECT_DOUBLE_EQ(ServoModel::torque(p, 1.0, 0.0, 0.0, 0.0), 0.0);
  EXPECT_NEAR(ServoModel::torque(p, 0.01, 0.0, 0.0, 1.0), p.kp * 0.01, 1e-12);
}

TEST(World, FindsRobotAndPlacesItOnTheCarpet) {
  World world(robotScene());
  EXPECT_EQ(world.robotCount(), 1);
  EXPECT_NEAR(world.model()->opt.timestep, 0.002, 1e-12);
  world.placeRobot(0, Eigen::Vector3d(1.0, -0.5, 0.3), posture());
  const Eigen::Vector3d pose = world.robotPose(0);
  EXPECT_NEAR(pose.x(), 1.0, 1e-9);
  EXPECT_NEAR(pose.y(), -0.5, 1e-9);
  EXPECT_NEAR(pose.z(), 0.3, 1e-9);
  const mjModel* m = world.model();
  const mjData* d = world.data();
  for (const char* sole : {"r0/LSole", "r0/RSole"}) {
    const int id = mj_name2id(m, mjOBJ_SITE, sole);
    ASSERT_GE(id, 0) << sole;
    EXPECT_NEAR(d->site_xpos[3 * id + 2], 0.0, 1e-3) << sole;
  }
  const SensorFrame f = world.sensors(0);
  for (int j = 0; j < NumJoints; ++j) {
    if (j == LHand || j == RHand) continue;
    EXPECT_NEAR(f.joints.position[j], posture()[j], 1e-9) << kJointNames[j];
    EXPECT_EQ(f.joints.stiffness[j], 1.0);
  }
}

TEST(World, ServosTrackWithinTheSpeedLimitAndHipYawPitchIsCoupled) {
  World world(robotScene());
  JointArray p = posture();
  p[LHipYawPitch] = -0.1;
  world.placeRobot(0, Eigen::Vector3d(0, 0, 0), p);
  const int rHyp = mj_name2id(world.model(), mjOBJ_JOINT, "r0/RHipYawPitch");
  ASSERT_GE(rHyp, 0);
  EXPECT_DOUBLE_EQ(world.data()->qpos[world.model()->jnt_qposadr[rHyp]], -0.1);
  JointRequest request;
  request.position = p;
  request.stiffness.fill(1.0);
  request.position[HeadYaw] = 1.5;  // a big step: the servo runs at its speed limit
  world.setJointRequest(0, request);
  const double limit = world.model()->actuator_user[mj_name2id(world.model(), mjOBJ_ACTUATOR, "r0/HeadYaw") *
                                                    world.model()->nuser_actuator];
  double fastest = 0, reached = -1, previous = 0;
  while (world.time() < 1.0) {
    world.stepCycle();
    const SensorFrame f = world.sensors(0);
    fastest = std::max(fastest, (f.joints.position[HeadYaw] - previous) / 0.012);
    previous = f.joints.position[HeadYaw];
    if (reached < 0 && std::abs(f.joints.position[HeadYaw] - 1.5) < 0.02) reached = world.time();
  }
  std::printf("HeadYaw step to 1.5 rad: fastest %.2f rad/s (no-load %.2f), within 0.02 rad after %.3f s\n", fastest,
              limit, reached);
  EXPECT_LE(fastest, limit * 1.001);
  EXPECT_GT(fastest, limit * 0.6);
  EXPECT_GT(reached, 1.5 / limit);
  EXPECT_LT(reached, 0.5);
  const SensorFrame f = world.sensors(0);
  EXPECT_NEAR(world.data()->qpos[world.model()->jnt_qposadr[rHyp]], f.joints.position[LHipYawPitch], 1e-3);
  EXPECT_NEAR(f.joints.position[LHipYawPitch], -0.1, 0.01);
}

TEST(World, BallDroppedComesToRestOnTheCarpet) {
  World world(ballScene());
  world.placeBall(0, Eigen::Vector3d(0.5, 0.5, 0.5));
  // At rest: slower than 1 mm/s for half a second (not just at the top of a bounce).
  double restTime = -1, slowSince = -1;
  while (world.time() < 5.0 && restTime < 0) {
    world.stepCycle();
    if (world.ballVelocity(0).norm() >= 1e-3) {
      slowSince = -1;
    } else if (slowSince < 0) {
      slowSince = world.time();
    } else if (world.time() - slowSince > 0.5) {
      restTime = slowSince;
    }
  }
  std::printf("ball dropped from 0.5 m: at rest after %.2f s, z = %.4f m\n", restTime, world.ballPosition(0).z());
  ASSERT_GT(restTime, 0) << "ball still moving at " << world.ballVelocity(0).norm() << " m/s";
  EXPECT_NEAR(world.ballPosition(0).z(), 0.05, 0.003);
}

// The foam ball's coefficient of restitution against hard surfaces (robot feet, goal posts),
// which sim/SceneBuilder.cpp models; the carpet absorbs the impact (BallDroppedComesToRest...).
constexpr double kBallRestitution = 0.5;

// Thrown at a goal post at kicking speeds (no spin, centre at the post's axis): it comes back
// at e times the speed (measured while it is in the air, before the carpet changes it).
TEST(World, BallReboundsOffAGoalPost) {
  World world(ballScene());
  const mjModel* m = world.model();
  mjData* d = world.data();
  const int post = mj_name2id(m, mjOBJ_GEOM, "goal/opp/post_left");
  const int joint = mj_name2id(m, mjOBJ_JOINT, "ball0");
  ASSERT_GE(post, 0);
  ASSERT_GE(joint, 0);
  const Eigen::Vector3d p(d->geom_xpos + 3 * post);
  for (double speed : {1.0, 2.0, 3.0}) {
    // 2 cm from the post: it arrives before gravity gives it much vertical speed.
    const double gap = m->geom_size[3 * post] + kBallRadius + 0.02;
    world.placeBall(0, Eigen::Vector3d(p.x() - gap, p.y(), 0.5), Eigen::Vector3d(speed, 0, 0));
    for (int i = 3; i < 6; ++i) d->qvel[m->jnt_dofadr[joint] + i] = 0;
    double rebound = 0;
    const double start = world.time();
    while (world.time() - start < 0.4 && world.ballPosition(0).z() > 0.15) {
      world.stepCycle();
      rebound = std::max(rebound, -world.ballVelocity(0).x());
    }
    const double e = rebound / speed;  // nothing slows it on its way to the post
    std::printf("ball thrown at a goal post at %.2f m/s: back at %.2f m/s, e = %.2f\n", speed, rebound, e);
    EXPECT_NEAR(e, kBallRestitution, 0.07);
  }
}

TEST(World, RolledBallStops) {
  World world(ballScene());
  world.placeBall(0, Eigen::Vector3d(-2.0, 0.0, 0.05), Eigen::Vector3d(1.5, 0.0, 0.0));
  while (world.time() < 20.0 && world.ballVelocity(0).norm() > 1e-3) world.stepCycle();
  const double distance = world.ballPosition(0).x() + 2.0;
  std::printf("ball rolled at 1.5 m/s: stopped after %.2f m in %.2f s\n", distance, world.time());
  EXPECT_LT(world.ballVelocity(0).norm(), 1e-3);
  // Placed rolling (its spin matches its speed): v^2 / 2a at the carpet's deceleration.
  EXPECT_NEAR(distance, 1.5 * 1.5 / (2 * kBallRollingDeceleration), 0.1);
}

TEST(World, PushIsAnImpulse) {
  World world(robotScene());
  world.placeRobot(0, Eigen::Vector3d(0, 0, 0), posture());
  const mjModel* m = world.model();
  mjData* d = world.data();
  const int torso = mj_name2id(m, mjOBJ_BODY, "r0/torso");
  const auto momentum = [&] {
    mj_subtreeVel(m, d);
    double mass = 0;
    for (int b = 0; b < m->nbody; ++b)
      if (m->body_rootid[b] == torso) mass += m->body_mass[b];
    return Eigen::Vector3d(Eigen::Vector3d(d->subtree_linvel + 3 * torso) * mass);
  };
  const Eigen::Vector3d before = momentum();
  world.pushRobot(0, Eigen::Vector3d(1.5, -0.5, 0.2));
  const Eigen::Vector3d change = momentum() - before;
  EXPECT_NEAR(change.x(), 1.5, 1e-9);
  EXPECT_NEAR(change.y(), -0.5, 1e-9);
  EXPECT_NEAR(change.z(), 0.2, 1e-9);
}

TEST(World, InjectedMiscalibrationIsExact) {
  World world(robotScene());
  world.placeRobot(0, Eigen::Vector3d(0.7, 0.2, -0.4), posture());
  const Eigen::Isometry3d torso = world.torsoPose(0);
  const Eigen::Isometry3d top0 = world.cameraPose(0, CameraId::Top);
  const Eigen::Isometry3d bottom0 = world.cameraPose(0, CameraId::Bottom);
  // The nominal mounts (docs/conventions.md): top pitched down 1.2 deg, bottom 39.7 deg.
  const Eigen::Matrix3d inTorsoTop = torso.linear().transpose() * top0.linear();
  const Eigen::Matrix3d inTorsoBottom = torso.linear().transpose() * bottom0.linear();
  EXPECT_NEAR(std::asin(-inTorsoTop(2, 0)), 1.2 * M_PI / 180, 1e-6);
  EXPECT_NEAR(std::asin(-inTorsoBottom(2, 0)), 39.7 * M_PI / 180, 1e-6);

  CameraCalibration c;
  c.bodyRoll = 0.031;
  c.bodyPitch = -0.047;
  c.topRoll = -0.022;
  c.topPitch = 0.058;
  c.bottomRoll = 0.041;
  c.bottomPitch = -0.036;
  world.setMiscalibration(0, c);
  EXPECT_EQ(world.miscalibration(0).toArray(), c.toArray());
  // T_field_cam' = T_field_torso * C_body * (T_field_torso^-1 T_field_cam) * C_cam.
  Eigen::Isometry3d body = Eigen::Isometry3d::Identity();
  body.linear() = rx(c.bodyRoll) * ry(c.bodyPitch);
  Eigen::Isometry3d camTop = Eigen::Isometry3d::Identity(), camBottom = Eigen::Isometry3d::Identity();
  camTop.linear() = rx(c.topRoll) * ry(c.topPitch);
  camBottom.linear() = rx(c.bottomRoll) * ry(c.bottomPitch);
  const Eigen::Isometry3d expectTop = torso * body * torso.inverse() * top0 * camTop;
  const Eigen::Isometry3d expectBottom = torso * body * torso.inverse() * bottom0 * camBottom;
  const Eigen::Isometry3d top = world.cameraPose(0, CameraId::Top);
  const Eigen::Isometry3d bottom = world.cameraPose(0, CameraId::Bottom);
  EXPECT_LT((top.matrix() - expectTop.matrix()).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((bottom.matrix() - expectBottom.matrix()).cwiseAbs().maxCoeff(), 1e-9);
  // The torso did not move, and resetting restores the nominal mounts.
  EXPECT_LT((world.torsoPose(0).matrix() - torso.matrix()).cwiseAbs().maxCoeff(), 1e-12);
  world.setMiscalibration(0, CameraCalibration{});
  EXPECT_LT((world.cameraPose(0, CameraId::Top).matrix() - top0.matrix()).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(World, CameraFrameUsesBHumanAxes) {
  World world(robotScene());
  world.placeRobot(0, Eigen::Vector3d(0, 0, 0), posture());
  const Eigen::Isometry3d top = world.cameraPose(0, CameraId::Top);
  // Head straight, robot facing +x: optical axis forward (slightly down), y left, z up.
  EXPECT_GT(top.linear()(0, 0), 0.99);
  EXPECT_GT(top.linear()(1, 1), 0.99);
  EXPECT_GT(top.linear()(2, 2), 0.99);
  EXPECT_NEAR(top.linear().determinant(), 1.0, 1e-12);
  EXPECT_NEAR(world.cameraFovY(), 43.7 * M_PI / 180, 1e-6);
}

TEST(World, NaNStopsTheSimulationNamingTheJoint) {
  World world(robotScene());
  world.placeRobot(0, Eigen::Vector3d(0, 0, 0), posture());
  world.stepCycle();
  const int knee = mj_name2id(world.model(), mjOBJ_JOINT, "r0/LKneePitch");
  ASSERT_GE(knee, 0);
  world.data()->qvel[world.model()->jnt_dofadr[knee]] = std::nan("");
  try {
    world.stepCycle();
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.where(), "simulation");
    EXPECT_NE(what.find("NaN in r0/LKneePitch"), std::string::npos) << what;
    EXPECT_NE(what.find("qvel"), std::string::npos) << what;
    std::printf("NaN message: %s\n", what.c_str());
  }
}

TEST(World, BadRequestIsRejected) {
  World world(robotScene());
  JointRequest r;
  r.position[HeadYaw] = std::nan("");
  EXPECT_THROW(world.setJointRequest(0, r), Error);
  EXPECT_THROW(world.setJointRequest(3, JointRequest{}), Error);
  EXPECT_THROW(world.placeBall(0, Eigen::Vector3d::Zero()), Error);  // no ball in this scene
}

TEST(World, SensorsAndTouch) {
  World world(robotScene());
  world.setTouch(0, ChestButton, 1.0);
  const SensorFrame f = world.sensors(0);
  EXPECT_EQ(f.touch[ChestButton], 1.0);
  EXPECT_EQ(f.touch[HeadFront], 0.0);
  EXPECT_EQ(f.battery.charge, 1.0);
  EXPECT_EQ(f.joints.temperature[LKneePitch], 30.0);
}

TEST(SimBackend, SeveralRobotsShareOneSteppedWorld) {
  SceneSpec spec;
  spec.robots = {Eigen::Vector3d(-1, 0, 0), Eigen::Vector3d(1, 0.5, M_PI)};
  World world(spec);
  ASSERT_EQ(world.robotCount(), 2);
  world.placeRobot(0, spec.robots[0], posture());
  world.placeRobot(1, spec.robots[1], posture());
  SimBackend a(world, 0, false), b(world, 1, false);
  EXPECT_EQ(b.robotInfo().headId, "sim-r1-head");
  SensorFrame fa, fb;
  for (int cycle = 0; cycle < 100; ++cycle) {
    world.stepCycle();  // the scenario steps; the backends only read
    ASSERT_TRUE(a.waitForSensors(fa));
    ASSERT_TRUE(b.waitForSensors(fb));
    EXPECT_DOUBLE_EQ(fa.time, world.time());
    EXPECT_DOUBLE_EQ(fb.time, world.time());
  }
  EXPECT_NEAR(world.time(), 1.2, 1e-9);
  EXPECT_NEAR(world.robotPose(1).x(), 1.0, 0.01);
  EXPECT_NEAR(std::abs(world.robotPose(1).z()), M_PI, 0.02);
  // Each robot's feet carry its own weight only.
  const double total = fa.fsr.total(true) + fa.fsr.total(false);
  EXPECT_NEAR(total, fb.fsr.total(true) + fb.fsr.total(false), 0.05 * total);
  EXPECT_NEAR(total, 5.36, 0.3);
}

TEST(SimBackend, StepsTheWorldAndDeliversImagesAt30Hz) {
  World world(robotScene());
  world.placeRobot(0, Eigen::Vector3d(0, 0, 0), posture());
  SimBackend backend(world, 0);
  int renders[2] = {0, 0};
  backend.setImageSource([&](CameraId camera, double, const ExposureWeights&) {
    ++renders[static_cast<int>(camera)];
    CameraImage image;
    image.width = 4;
    image.height = 2;
    image.yuyv.assign(16, 128);
    return image;
  });
  EXPECT_EQ(backend.name(), "sim");
  EXPECT_EQ(backend.robotInfo().bodyId, "sim-r0-body");
  SensorFrame frame;
  int taken[2] = {0, 0};
  double lastTop = -1;
  JointRequest request;
  request.position = posture();
  request.stiffness.fill(1.0);
  for (int cycle = 0; cycle < 250; ++cycle) {  // 3 s
    ASSERT_TRUE(backend.waitForSensors(frame));
    EXPECT_EQ(frame.cycle, static_cast<std::uint64_t>(cycle));
    EXPECT_NEAR(frame.time, 0.012 * (cycle + 1), 1e-9);
    CameraImage image;
    for (int c = 0; c < 2; ++c) {
      if (backend.takeImage(static_cast<CameraId>(c), image)) {
        ++taken[c];
        EXPECT_EQ(image.camera, static_cast<CameraId>(c));
        EXPECT_NEAR(image.timestamp, frame.time, 1e-12);
        if (c == 0) {
          if (lastTop >= 0) {
            // Due every 1/30 s, delivered on the 12 ms cycle grid: 2 or 3 cycles apart.
            EXPECT_GE(image.timestamp - lastTop, 0.024 - 1e-9);
            EXPECT_LE(image.timestamp - lastTop, 0.036 + 1e-9);
          }
          lastTop = image.timestamp;
        }
        EXPECT_FALSE(backend.takeImage(static_cast<CameraId>(c), image));  // once only
      }
    }
    backend.sendRequest(request, LedRequest{});
  }
  EXPECT_NEAR(renders[0], 90, 1);
  EXPECT_NEAR(renders[1], 90, 1);
  EXPECT_EQ(taken[0], renders[0]);
  EXPECT_EQ(taken[1], renders[1]);
  backend.stop("end of test");
  EXPECT_FALSE(backend.waitForSensors(frame));
  EXPECT_EQ(backend.stopReason(), "end of test");
}

}  // namespace
}  // namespace nao::sim
