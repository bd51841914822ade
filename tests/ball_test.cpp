// The ball detector against independent truth:
// - synthetic images: grass, paint and spheres ray-traced through the camera model (so the
//   true pixel and radius are exact), a black-and-white ball, smoothly shaded spheres without
//   a pattern (what a robot's shoulder or a goal post's foot looks like), dim and warm light,
//   motion blur, a ball in front of a dark trouser leg;
// - simulated images (sim::World + CameraRenderer): balls at known positions in both cameras
//   under every lighting preset of the sweep, on lines in front of the goal, beside the own
//   feet; the robot's own shoulder and arm in the bottom camera and goal posts never give a
//   ball. Truth is the simulator's ball position and its own projection.
#include <gtest/gtest.h>

#include <mujoco/mujoco.h>

#include <cmath>
#include <functional>
#include <random>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

#include "controllers/StandController.h"
#include "perception/CameraModel.h"
#include "support/StandingCamera.h"
#include "support/SyntheticScene.h"
#include "perception/Geometry.h"
#include "perception/vision/BallDetector.h"
#include "perception/vision/VisionPipeline.h"
#include "robot/ForwardKinematics.h"
#include "robot/Paths.h"
#include "scenarios/ProgramMetering.h"
#include "sim/CameraRenderer.h"
#include "sim/GroundTruth.h"
#include "sim/ImageIO.h"
#include "sim/Lighting.h"
#include "sim/World.h"

namespace nao {
namespace {

constexpr double kDeg = M_PI / 180;
constexpr double kBallR = 0.05;

// ---------------------------------------------------------------------------------------
// Synthetic images.

using test::standingCamera;

using test::kNoPaint;
using test::Light;
using test::plain;
using test::soccerBall;
using test::Sphere;
using test::syntheticImage;

const std::vector<std::pair<const char*, Light>> kLights = {
    {"normal", {1.0, {1, 1, 1}, 2.0}}, {"dim", {0.25, {1, 1, 1}, 1.5}}, {"warm", {0.9, {1.0, 0.72, 0.42}, 2.0}}};

Eigen::Matrix3d turn(double a, double b) {
  return (Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(b, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

// The ball's true pixel and image radius (the sphere's silhouette), from the camera model.
void truePixel(const CameraMatrix& cm, const Eigen::Vector2d& ball, Eigen::Vector2d& px, double& radiusPx) {
  const Eigen::Vector3d c(ball.x(), ball.y(), kBallR);
  px = *cm.project(c);
  radiusPx = cm.intrinsics.fy * std::tan(std::asin(kBallR / (c - cm.pose.translation()).norm()));
}

TEST(BallSynthetic, FoundWhereItLiesInEveryLight) {
  const CameraMatrix cm = standingCamera(0, 14);
  const std::vector<Eigen::Vector2d> balls = {{0.9, 0.15}, {1.5, -0.4}, {2.5, 0.5}, {3.5, -0.6}};
  int k = 0;
  for (const auto& [name, light] : kLights)
    for (const Eigen::Vector2d& ball : balls) {
      SCOPED_TRACE(std::string(name) + " ball at " + std::to_string(ball.x()) + "," + std::to_string(ball.y()));
      const Sphere s{Eigen::Vector3d(ball.x(), ball.y(), kBallR), kBallR, soccerBall(turn(0.7 * k, 0.4 * k))};
      ++k;
      const VisionResult r = runVision(syntheticImage(cm, {s}, kNoPaint, light), cm);
      ASSERT_TRUE(r.ball.seen);
      Eigen::Vector2d px;
      double radiusPx;
      truePixel(cm, ball, px, radiusPx);
      EXPECT_LT((r.ball.position - ball).norm(), 0.05 * ball.norm()) << r.ball.position.transpose();
      EXPECT_LT((r.ball.image - px).norm(), std::max(1.5, 0.15 * radiusPx)) << r.ball.image.transpose();
      EXPECT_NEAR(r.ball.radiusPx, radiusPx, std::max(1.0, 0.15 * radiusPx));
    }
}

TEST(BallSynthetic, FoundOnALineAndAtALineEnd) {
  // A ball on a line merges with the line's white run on the scan lines; its black patches
  // still seed a candidate, and the outline is fitted to where the field is.
  const CameraMatrix cm = standingCamera(0, 18);
  auto line = [](const Eigen::Vector2d& p) { return std::abs(p.y() + 0.02) <= 0.025 && p.x() > 0.3 && p.x() < 4; };
  auto cross = [](const Eigen::Vector2d& p) {
    return (std::abs(p.x() - 1.2) <= 0.025 && std::abs(p.y()) < 2) || (std::abs(p.y() - 0.4) <= 0.025 && p.x() > 1.2);
  };
  struct Case {
    Eigen::Vector2d ball;
    std::function<bool(const Eigen::Vector2d&)> paint;
  };
  const std::vector<Case> cases = {{{0.9, 0.0}, line}, {{1.6, -0.03}, line}, {{1.2, 0.1}, cross}, {{1.25, 0.4}, cross}};
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(i);
    const Eigen::Vector2d ball = cases[i].ball;
    const Sphere s{Eigen::Vector3d(ball.x(), ball.y(), kBallR), kBallR, soccerBall(turn(1.1 * i, 0.3))};
    const VisionResult r = runVision(syntheticImage(cm, {s}, cases[i].paint), cm);
    ASSERT_TRUE(r.ball.seen);
    EXPECT_LT((r.ball.position - ball).norm(), 0.05 * ball.norm()) << r.ball.position.transpose();
  }
}

TEST(BallSynthetic, ShadedSpheresWithoutAPatternAreNoBall) {
  // Smoothly shaded spheres of the ball's size (grey like a robot's joint, white like its
  // shell or a goal post's foot): the light gives them a bright and a dark side, but no
  // black patches. The ball next to them is found.
  const CameraMatrix cm = standingCamera(0, 14);
  for (const auto& [name, light] : kLights) {
    SCOPED_TRACE(name);
    const std::vector<Sphere> decoys = {{Eigen::Vector3d(1.0, 0.3, kBallR), kBallR, plain(0.45)},
                                        {Eigen::Vector3d(1.8, -0.5, kBallR), kBallR, plain(0.9)},
                                        {Eigen::Vector3d(2.6, 0.6, kBallR), kBallR, plain(0.25)}};
    std::vector<vision::BallCandidate> candidates;
    const VisionResult r = runVision(syntheticImage(cm, decoys, kNoPaint, light), cm);
    EXPECT_FALSE(r.ball.seen) << "at " << r.ball.position.transpose();
    // With a ball among them, the ball is what is found.
    std::vector<Sphere> withBall = decoys;
    withBall.push_back({Eigen::Vector3d(1.4, 0.05, kBallR), kBallR, soccerBall(turn(0.3, 0.9))});
    const VisionResult rb = runVision(syntheticImage(cm, withBall, kNoPaint, light), cm);
    ASSERT_TRUE(rb.ball.seen);
    EXPECT_LT((rb.ball.position - Eigen::Vector2d(1.4, 0.05)).norm(), 0.07);
  }
}

TEST(BallSynthetic, FoundInFrontOfADarkLeg) {
  // A ball at a person's feet: a dark trouser leg (a column of dark spheres, about the ball's
  // width) stands right behind it and rises above it in the image. Narrow and upright like a
  // goal post above its foot, but far darker than the ball's white: not the ball's surface
  // carrying on upwards (real image 00268).
  const CameraMatrix cm = standingCamera(0, 14);
  const std::vector<Eigen::Vector2d> balls = {{1.0, 0.1}, {1.6, -0.2}, {2.2, 0.3}};
  int k = 0;
  for (const auto& [name, light] : kLights)
    for (const Eigen::Vector2d& ball : balls) {
      SCOPED_TRACE(std::string(name) + " ball at " + std::to_string(ball.x()) + "," + std::to_string(ball.y()));
      std::vector<Sphere> scene = {
          {Eigen::Vector3d(ball.x(), ball.y(), kBallR), kBallR, soccerBall(turn(0.9 * k, 0.5 + 0.3 * k))}};
      ++k;
      for (int i = 0; i < 10; ++i)
        scene.push_back({Eigen::Vector3d(ball.x() + 0.11, ball.y(), 0.055 + 0.07 * i), 0.055, plain(0.1)});
      const VisionResult r = runVision(syntheticImage(cm, scene, kNoPaint, light), cm);
      ASSERT_TRUE(r.ball.seen);
      Eigen::Vector2d px;
      double radiusPx;
      truePixel(cm, ball, px, radiusPx);
      EXPECT_LT((r.ball.position - ball).norm(), 0.05 * ball.norm()) << r.ball.position.transpose();
      EXPECT_LT((r.ball.image - px).norm(), std::max(1.5, 0.15 * radiusPx)) << r.ball.image.transpose();
    }
}

TEST(BallSynthetic, TheVerifierTellsPatchesFromShading) {
  // The measurements behind the decision: a ball's black patches are dark relative to its
  // white and are patches (luminance left after mean and gradient on the rings); a shaded
  // sphere has contrast from its dark side but no pattern.
  const CameraMatrix cm = standingCamera(0, 14);
  auto measure = [&](const Sphere& s) {
    const CameraImage img = syntheticImage(cm, {s}, kNoPaint);
    const VisionResult r = runVision(img, cm);
    std::vector<vision::BallCandidate> cands;
    vision::detectBall(img, r.regions, vision::FieldReference::from(r.regions), r.obstacles, cm, vision::BallParams{},
                       &cands);
    Eigen::Vector2d px;
    double radiusPx;
    truePixel(cm, s.centre.head<2>(), px, radiusPx);
    vision::BallCandidate best;
    for (const auto& c : cands)
      if (c.fitted && c.contrast > 0 && (c.centre - px).norm() < 0.5 * radiusPx) best = c;
    return best;
  };
  const vision::BallCandidate ball = measure({Eigen::Vector3d(1.3, 0.1, kBallR), kBallR, soccerBall(turn(0.2, 0.5))});
  const vision::BallCandidate grey = measure({Eigen::Vector3d(1.3, 0.1, kBallR), kBallR, plain(0.5)});
  ASSERT_GT(ball.contrast, 0);
  ASSERT_GT(grey.contrast, 0) << "the grey sphere must be measured (fitted like a ball)";
  EXPECT_GT(ball.contrast, 0.8);
  EXPECT_GT(ball.pattern, 0.15);
  EXPECT_LT(grey.pattern, vision::BallParams{}.minPattern);
  EXPECT_GT(ball.support, 0.9);
  EXPECT_TRUE(ball.accepted);
  EXPECT_FALSE(grey.accepted);
}

TEST(BallSynthetic, MotionBlurredBallOnOpenField) {
  // Blur smears the patches into grey (the contrast drops, as on a real robot turning its
  // head): a clean outline all round on the field still makes it a ball.
  const CameraMatrix cm = standingCamera(0, 14);
  const Eigen::Vector2d ball(1.2, -0.1);
  Eigen::Vector2d px;
  double radiusPx;
  truePixel(cm, ball, px, radiusPx);
  const Sphere s{Eigen::Vector3d(ball.x(), ball.y(), kBallR), kBallR, soccerBall(turn(0.5, 0.2))};
  const CameraImage img = syntheticImage(cm, {s}, kNoPaint, {}, CameraId::Top, 0.8 * radiusPx);
  const VisionResult r = runVision(img, cm);
  std::vector<vision::BallCandidate> cands;
  vision::detectBall(img, r.regions, vision::FieldReference::from(r.regions), r.obstacles, cm, {}, &cands);
  // The blur must really have smeared the pattern (below a clear one's contrast).
  int measured = 0;
  for (const auto& c : cands)
    if (c.fitted && c.contrast > 0 && (c.centre - px).norm() < 0.5 * radiusPx) {
      ++measured;
      EXPECT_LT(c.contrast, vision::BallParams{}.clearContrast);
    }
  EXPECT_GT(measured, 0);
  ASSERT_TRUE(r.ball.seen);
  EXPECT_LT((r.ball.position - ball).norm(), 0.06 * ball.norm());
}

TEST(BallSynthetic, NoBallOnEmptyGrassAndLines) {
  const CameraMatrix cm = standingCamera(10, 12);
  auto lines = [](const Eigen::Vector2d& p) {
    return std::abs(p.x() - 1.5) <= 0.025 || std::abs(p.y() - 0.6) <= 0.025 ||
           std::abs((p - Eigen::Vector2d(3, 0)).norm() - 0.75) <= 0.025;
  };
  for (const auto& [name, light] : kLights) {
    SCOPED_TRACE(name);
    EXPECT_FALSE(runVision(syntheticImage(cm, {}, kNoPaint, light), cm).ball.seen);
    EXPECT_FALSE(runVision(syntheticImage(cm, {}, lines, light), cm).ball.seen);
  }
}

TEST(BallSynthetic, NothingWithoutAFieldColour) {
  // No field found (a grey image): no candidates, no ball, no crash.
  const CameraMatrix cm = standingCamera(0, 12);
  cv::Mat grey(cm.intrinsics.height, cm.intrinsics.width, CV_8UC3, cv::Scalar(120, 120, 120));
  const CameraImage img = sim::cameraImageFromRgb(grey);
  const VisionResult r = runVision(img, cm);
  std::vector<vision::BallCandidate> cands;
  const BallPercept b =
      vision::detectBall(img, r.regions, vision::FieldReference::from(r.regions), r.obstacles, cm, {}, &cands);
  EXPECT_FALSE(b.seen);
  EXPECT_FALSE(r.ball.seen);
}

// ---------------------------------------------------------------------------------------
// Simulated images.

class BallScene : public ::testing::Test {
 protected:
  void SetUp() override {
    sim::SceneSpec spec;
    spec.field = FieldDimensions::load(dataPath("config/field_dimensions.json"));
    spec.balls = {Eigen::Vector3d(1, 0, kBallR)};
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
    world_->placeBall(0, Eigen::Vector3d(ball.x(), ball.y(), kBallR));
    const sim::Lighting lighting = sim::Lighting::parse(preset, dataPath("config/lighting.json"));
    const sim::CameraResolution res = world_->cameraResolution(camera);
    const SensorFrame s = world_->sensors(0);
    cm_ = computeCameraMatrix(s.joints.position, s.inertial.angle, camera, CameraCalibration{},
                              CameraIntrinsics::fromFovY(res.width, res.height, world_->cameraFovY()));
    // Exposed as the robot program meters this view (its AutoExposureWeighting).
    static const ProgramMetering metering(dataPath("config"));
    const ExposureWeights weights = metering(cm_, s, CameraCalibration{});
    renderer_->resetCameraSensors();  // a settled camera at each placed view, not a jump from the last
    image_ = renderer_->renderImage(world_->model(), world_->data(), world_->cameraIndex(0, camera), res.width,
                                    res.height, lighting, camera, 0, rng_, weights);
    return runVision(image_, cm_);
  }

  // Is the percept the true ball (field frame, within 5 % of its distance from the camera)?
  bool isTheBall(const VisionResult& r, const Eigen::Vector2d& ball, CameraId camera) const {
    if (!r.ball.seen) return false;
    const Eigen::Vector2d seen = robotToField(r.ball.position, world_->robotPose(0));
    const double dist = (ball - world_->cameraPose(0, camera).translation().head<2>()).norm();
    return (seen - ball).norm() < 0.05 * dist;
  }

  // Points on one of the robot's own geoms (field frame): its centre and, for a capsule,
  // points along its axis.
  std::vector<Eigen::Vector3d> geomPoints(const char* name) const {
    const mjModel* m = world_->model();
    const int g = mj_name2id(m, mjOBJ_GEOM, (std::string("r0/") + name).c_str());
    EXPECT_GE(g, 0) << name;
    if (g < 0) return {};
    const double* p = world_->data()->geom_xpos + 3 * g;
    const double* r = world_->data()->geom_xmat + 9 * g;
    const Eigen::Vector3d centre(p[0], p[1], p[2]), axis(r[2], r[5], r[8]);
    std::vector<Eigen::Vector3d> out = {centre};
    if (m->geom_type[g] == mjGEOM_CAPSULE)
      for (double t : {-1.0, -0.5, 0.5, 1.0}) out.push_back(centre + t * m->geom_size[3 * g + 1] * axis);
    if (m->geom_type[g] == mjGEOM_SPHERE)
      for (int k = 0; k < 3; ++k)
        for (double t : {-1.0, 1.0}) out.push_back(centre + t * m->geom_size[3 * g] * Eigen::Vector3d::Unit(k));
    return out;
  }

  std::unique_ptr<sim::World> world_;
  std::unique_ptr<sim::CameraRenderer> renderer_;
  std::mt19937_64 rng_{5};
  CameraMatrix cm_;
  CameraImage image_;
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
    EXPECT_NEAR(vision::expectedBallRadius(cm_, truth.balls[0].image, kBallR), truth.balls[0].radiusPx,
                0.05 * truth.balls[0].radiusPx + 0.3);
  }
}

TEST_F(BallScene, FoundUnderEveryLightingPresetInBothCameras) {
  // Same scenes under every preset of the sweep (x0.25 to x2.5, 2700 K to 6500 K, hard
  // shadows, noise): the figures must not depend on the light.
  struct View {
    Eigen::Vector3d pose;
    double yaw, pitch;
    Eigen::Vector2d ball;
    CameraId camera;
  };
  const std::vector<View> views = {
      {{1, -1, 90 * kDeg}, -5, 12, {1.3, 1.0}, CameraId::Top},          // 2 m
      {{-1, 1, 0}, 20, 0, {2.6, 2.2}, CameraId::Top},                   // 4 m, to the side
      {{-0.45, 0.3, 0}, 0, 10, {-0.05, 0.45}, CameraId::Bottom},        // at the feet, by the centre line
      {{-3, 0, 180 * kDeg}, 35, 0, {-3.6, -0.5}, CameraId::Bottom}};  // turned head
  for (const auto& l : sim::Lighting::sweep(dataPath("config/lighting.json")))
    for (std::size_t i = 0; i < views.size(); ++i) {
      SCOPED_TRACE(l.name + " view " + std::to_string(i));
      const View& v = views[i];
      const VisionResult r = look(v.pose, v.yaw, v.pitch, v.ball, v.camera, l.name);
      ASSERT_EQ(sim::visibleFeatures(*world_, 0, v.camera).balls.size(), 1u) << "the scene must show the ball";
      EXPECT_TRUE(isTheBall(r, v.ball, v.camera)) << (r.ball.seen ? "elsewhere" : "not seen");
    }
}

TEST_F(BallScene, FoundOnTheLinesInFrontOfTheGoal) {
  // Balls lying on the goal box and penalty area lines about 0.9 m in front of the robot,
  // which faces the goal: the ball's white merges with the line's on the scan lines.
  const FieldModel& field = world_->field();
  const double goalX = field.halfLength();
  const double boxX = goalX - field.dims.goalBoxAreaLength;
  const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector2d>> scenes = {
      {{boxX - 0.9, 0.2, 0}, {boxX, 0.2}},             // on the goal box line, straight ahead
      {{boxX - 0.8, -0.3, 10 * kDeg}, {boxX, -0.15}},  // slightly to the side
      {{goalX - 1.0, 0.0, 0}, {goalX - 0.1, 0.0}}};    // just in front of the goal line
  for (const auto& l : sim::Lighting::sweep(dataPath("config/lighting.json")))
    for (std::size_t i = 0; i < scenes.size(); ++i) {
      SCOPED_TRACE(l.name + " scene " + std::to_string(i));
      const auto& [pose, ball] = scenes[i];
      VisionResult r = look(pose, 0, 20, ball, CameraId::Top, l.name);
      if (!sim::visibleFeatures(*world_, 0, CameraId::Top).balls.empty()) {
        EXPECT_TRUE(isTheBall(r, ball, CameraId::Top)) << "top " << (r.ball.seen ? "elsewhere" : "not seen");
      } else {
        r = look(pose, 0, 20, ball, CameraId::Bottom, l.name);
        ASSERT_EQ(sim::visibleFeatures(*world_, 0, CameraId::Bottom).balls.size(), 1u);
        EXPECT_TRUE(isTheBall(r, ball, CameraId::Bottom)) << "bottom " << (r.ball.seen ? "elsewhere" : "not seen");
      }
    }
}

TEST_F(BallScene, OwnShoulderAndArmInTheBottomCameraAreNoBall) {
  // Head turned far to a side and down: the bottom camera sees the robot's own shoulder
  // joint (a grey sphere) and upper arm (a white capsule) against the field. The ball is far
  // behind the robot. No percept under any light.
  struct Head {
    double yaw, pitch;
  };
  const std::vector<Head> heads = {{-64, 22}, {-55, 22}, {62, 23}, {55, 22}, {83, -4}, {63, -3}};
  int armInView = 0, frames = 0, percepts = 0;
  for (const auto& l : sim::Lighting::sweep(dataPath("config/lighting.json")))
    for (const Head& h : heads) {
      SCOPED_TRACE(l.name + " head " + std::to_string(h.yaw) + "," + std::to_string(h.pitch));
      const Eigen::Vector3d pose(-0.5, 0.5, 30 * kDeg);
      const Eigen::Vector2d behind = pose.head<2>() - 3 * Eigen::Vector2d(std::cos(pose.z()), std::sin(pose.z()));
      const VisionResult r = look(pose, h.yaw, h.pitch, behind, CameraId::Bottom, l.name);
      ++frames;
      // The truth: is the own shoulder or upper arm on the image?
      bool inView = false;
      for (const char* g : {"LShoulder_geom", "LBicep_geom", "RShoulder_geom", "RBicep_geom"})
        for (const Eigen::Vector3d& p : geomPoints(g))
          if (const auto px = sim::truePixel(*world_, 0, CameraId::Bottom, p))
            inView = inView || (px->x() >= 0 && px->y() >= 0 && px->x() < image_.width && px->y() < image_.height);
      armInView += inView;
      percepts += r.ball.seen;
      EXPECT_FALSE(r.ball.seen) << "false ball at " << r.ball.image.transpose() << " r " << r.ball.radiusPx;
    }
  EXPECT_GE(armInView, frames * 2 / 3) << "the views must show the own arm";
  EXPECT_EQ(percepts, 0);
}

TEST_F(BallScene, GoalPostsAreNoBall) {
  // Standing in front of a goal, the posts' feet on the field (round, white, shaded) in view
  // in the top camera; the ball far behind.
  const double goalX = world_->field().halfLength();
  const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector2d>> views = {
      {{goalX - 1.5, 0.0, 0}, {0, 0}},
      {{goalX - 2.5, 1.2, -15 * kDeg}, {0, 5}},
      {{goalX - 1.2, -1.0, 30 * kDeg}, {-10, 12}}};
  const FieldDimensions& dims = world_->field().dims;
  const double postY = 0.5 * (dims.goalInnerWidth + dims.goalPostDiameter);
  int percepts = 0, frames = 0, footInView = 0;
  for (const auto& l : sim::Lighting::sweep(dataPath("config/lighting.json")))
    for (const auto& [pose, head] : views) {
      SCOPED_TRACE(l.name);
      const Eigen::Vector2d behind = pose.head<2>() - 3 * Eigen::Vector2d(std::cos(pose.z()), std::sin(pose.z()));
      const VisionResult r = look(pose, head.x(), head.y(), behind, CameraId::Top, l.name);
      ++frames;
      // The truth: a post's foot (just above the carpet, on the goal line) on the image.
      bool inView = false;
      for (double side : {-1.0, 1.0})
        if (const auto px = sim::truePixel(*world_, 0, CameraId::Top,
                                           Eigen::Vector3d(goalX + 0.5 * dims.goalPostDiameter, side * postY, 0.05)))
          inView = inView || (px->x() >= 0 && px->y() >= 0 && px->x() < image_.width && px->y() < image_.height);
      footInView += inView;
      percepts += r.ball.seen;
      EXPECT_FALSE(r.ball.seen) << "false ball at " << r.ball.image.transpose();
    }
  EXPECT_EQ(footInView, frames) << "every view must show a post's foot";
  EXPECT_EQ(percepts, 0);
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
