// The first half of the vision on simulated images, measured against the simulator's truth
// (the true camera pose from World::cameraPose, the field model, ray casts for occlusion),
// never against the detector: the same robot poses under every lighting preset (so the
// figures are comparable), both cameras.
// - field colour: truth-field pixels on the scan regions that are classified field;
// - white: white-region pixels on the carpet that lie on (or within 2 cm of) the paint;
// - field boundary: the detected boundary row against the carpet edge's image, per column
//   where the edge is in view and not hidden;
// - obstacles: another robot in view is inside an obstacle box.
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "controllers/StandController.h"
#include "perception/CameraModel.h"
#include "perception/Geometry.h"
#include "perception/vision/FieldBoundaryDetector.h"
#include "perception/vision/ObstacleDetector.h"
#include "perception/vision/ScanGrid.h"
#include "perception/vision/ScanLineRegionizer.h"
#include "perception/vision/VisionDebug.h"
#include "robot/Paths.h"
#include "sim/ImageIO.h"
#include "sim/CameraRenderer.h"
#include "sim/GroundTruth.h"
#include "sim/Lighting.h"
#include "sim/World.h"

namespace nao {
namespace {

bool onPaint(const FieldModel& f, const Eigen::Vector2d& p, double margin) {
  const double hw = f.dims.lineWidth / 2 + margin;
  for (const auto& l : f.lines) {
    const Eigen::Vector2d d = (l.to - l.from).normalized();
    const Eigen::Vector2d q = p - l.from;
    const double t = q.dot(d), n = std::abs(q.x() * d.y() - q.y() * d.x());
    if (t >= -hw && t <= (l.to - l.from).norm() + hw && n <= hw) return true;
  }
  if (std::abs((p - f.centerCircleCenter).norm() - f.centerCircleRadius) <= hw) return true;
  for (const auto& c : f.penaltyCrosses)
    if ((p - c).cwiseAbs().maxCoeff() <= f.dims.penaltyCrossSize / 2 + margin) return true;
  return (p - f.centerMark).cwiseAbs().maxCoeff() <= f.dims.penaltyCrossSize / 2 + margin;
}

bool onCarpet(const FieldModel& f, const Eigen::Vector2d& p) {
  return std::abs(p.x()) <= f.halfLength() + f.dims.borderStripWidth &&
         std::abs(p.y()) <= f.halfWidth() + f.dims.borderStripWidth;
}

// The true camera as a camera matrix in the field frame (robot pose 0).
CameraMatrix trueCamera(const sim::World& w, int robot, CameraId cam) {
  CameraMatrix cm;
  cm.pose = w.cameraPose(robot, cam);
  const auto res = w.cameraResolution(cam);
  cm.intrinsics = CameraIntrinsics::fromFovY(res.width, res.height, w.cameraFovY());
  return cm;
}

struct Figures {
  long fieldTruth = 0, fieldOk = 0, white = 0, whiteOnPaint = 0;
  std::vector<double> boundaryErr;
  int robotsInView = 0, robotsFound = 0, falseObstacles = 0, frames = 0;
  std::vector<double> ms;
  double field() const { return fieldTruth ? static_cast<double>(fieldOk) / fieldTruth : 1; }
  double whitePrecision() const { return white ? static_cast<double>(whiteOnPaint) / white : 1; }
  double boundaryQuantile(double q) const {
    if (boundaryErr.empty()) return 0;
    std::vector<double> e = boundaryErr;
    std::sort(e.begin(), e.end());
    return e[static_cast<std::size_t>(q * (e.size() - 1))];
  }
  double obstacleRecall() const { return robotsInView ? static_cast<double>(robotsFound) / robotsInView : 1; }
};

class SimulatedVision : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    sim::SceneSpec spec;
    spec.field = FieldDimensions::load(dataPath("config/field_dimensions.json"));
    spec.robots = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 1, 3.0)};
    spec.balls = {Eigen::Vector3d(1, 0.5, 0.05)};
    world_ = new sim::World(spec, 1);
    renderer_ = new sim::CameraRenderer(world_->model());
    // The same poses for every preset: the figures differ only by the light.
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    auto uni = [&](double a, double b) { return a + (b - a) * u(rng); };
    for (int i = 0; i < kPoses; ++i) {
      Pose p;
      p.robot = {uni(-4.0, 4.0), uni(-2.6, 2.6), uni(-M_PI, M_PI)};
      p.yaw = uni(-0.9, 0.9);
      p.pitch = uni(-0.15, 0.4);
      const double d = uni(0.9, 2.8), side = uni(-0.6, 0.6);
      const double heading = p.robot.z() + p.yaw;
      // In front of it, on the carpet.
      p.other = {std::clamp(p.robot.x() + d * std::cos(heading + side), -4.8, 4.8),
                 std::clamp(p.robot.y() + d * std::sin(heading + side), -3.3, 3.3), uni(-3, 3)};
      p.ball = {p.robot.x() + 0.8 * d * std::cos(heading - side), p.robot.y() + 0.8 * d * std::sin(heading - side), 0.05};
      poses_.push_back(p);
    }
  }
  static void TearDownTestSuite() {
    delete renderer_;
    delete world_;
    renderer_ = nullptr;
    world_ = nullptr;
  }

  struct Pose {
    Eigen::Vector3d robot, other, ball;
    double yaw = 0, pitch = 0;
  };
  static constexpr int kPoses = 8;

  static Figures run(const std::string& preset) {
    Figures f;
    const sim::Lighting light = sim::Lighting::parse(preset, dataPath("config/lighting.json"));
    std::mt19937_64 noiseRng(11);
    const FieldModel& field = world_->field();
    for (const Pose& pose : poses_) {
      JointArray posture = StandController::standPosture();
      posture[HeadYaw] = pose.yaw;
      posture[HeadPitch] = pose.pitch;
      world_->placeRobot(0, pose.robot, posture);
      world_->placeRobot(1, pose.other, StandController::standPosture());
      world_->placeBall(0, pose.ball);
      for (CameraId cam : {CameraId::Top, CameraId::Bottom}) {
        const auto res = world_->cameraResolution(cam);
        renderer_->resetCameraSensors();  // each pose a settled camera, not a jump from the last
        const CameraImage img = renderer_->renderImage(world_->model(), world_->data(), world_->cameraIndex(0, cam),
                                                       res.width, res.height, light, cam, 0, noiseRng, ExposureWeights{});
        const SensorFrame sensors = world_->sensors(0);
        const CameraMatrix cm = computeCameraMatrix(sensors.joints.position, sensors.inertial.angle, cam,
                                                    CameraCalibration{},
                                                    CameraIntrinsics::fromFovY(res.width, res.height, world_->cameraFovY()));
        const auto t0 = std::chrono::steady_clock::now();
        const FieldSegmentation seg = segmentField(img, cm);
        if (cam == CameraId::Top)
          f.ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        ++f.frames;
        const CameraMatrix truth = trueCamera(*world_, 0, cam);

        const long w0 = f.whiteOnPaint, w1 = f.white, f0 = f.fieldOk, f1 = f.fieldTruth;  // for NAO_VISION_FRAMES
        std::vector<cv::Point> falseWhite;
        // Regions, every third pixel.
        auto visit = [&](int x, int y, RegionClass c) {
          const auto g = truth.pixelToGround({x + 0.5, y + 0.5});
          if (!g || !onCarpet(field, *g)) return;
          if (!sim::trulyVisible(*world_, 0, cam, Eigen::Vector3d(g->x(), g->y(), 0.001))) return;
          // Within 2 cm or 2.5 px of the paint (a far line is thinner than a pixel and
          // blurred over three).
          const Eigen::Vector2d centre(x + 0.5, y + 0.5);
          const std::array<Eigen::Vector2d, 4> around = {Eigen::Vector2d(2.5, 0), Eigen::Vector2d(-2.5, 0),
                                                         Eigen::Vector2d(0, 2.5), Eigen::Vector2d(0, -2.5)};
          bool nearPaint = onPaint(field, *g, 0.02);
          for (double t = -2.5; t <= 2.5 && !nearPaint; t += 0.25)
            for (const Eigen::Vector2d& d : {Eigen::Vector2d(t, 0), Eigen::Vector2d(0, t)}) {
              const auto n = truth.pixelToGround(centre + d);
              nearPaint = nearPaint || (n && onPaint(field, *n, 0));
            }
          if (!nearPaint) f.fieldTruth++, f.fieldOk += c == RegionClass::Field;
          // White at the silhouette of a robot or the ball (within 2.5 px) is theirs.
          if (c == RegionClass::White && !nearPaint) {
            for (const auto& d : around) {
              const auto n = truth.pixelToGround(centre + d);
              if (n && !sim::trulyVisible(*world_, 0, cam, Eigen::Vector3d(n->x(), n->y(), 0.001))) return;
            }
          }
          if (c == RegionClass::White) {
            f.white++, f.whiteOnPaint += nearPaint;
            if (!nearPaint) falseWhite.emplace_back(x, y);
          }
        };
        for (const ScanLine& l : seg.regions.vertical)
          for (const ScanRegion& r : l.regions)
            for (int y = r.from; y < r.to; y += 3) visit(l.coord, y, r.cls);
        for (const ScanLine& l : seg.regions.horizontal)
          for (const ScanRegion& r : l.regions)
            for (int x = r.from; x < r.to; x += 3) visit(x, l.coord, r.cls);

        // Boundary: the topmost row whose ray meets the carpet, where that point is visible.
        for (int x = 4; x < res.width; x += 12) {
          int top = -1;
          for (int y = 0; y < res.height && top < 0; ++y) {
            const auto g = truth.pixelToGround({x + 0.5, y + 0.5});
            if (g && onCarpet(field, *g)) top = y;
          }
          if (top <= 0) continue;  // no carpet in this column, or it reaches above the image
          const auto g = truth.pixelToGround({x + 0.5, top + 0.5});
          if (!sim::trulyVisible(*world_, 0, cam, Eigen::Vector3d(g->x(), g->y(), 0.001))) continue;
          if (!seg.boundary.valid) {
            f.boundaryErr.push_back(res.height);
            continue;
          }
          f.boundaryErr.push_back(std::abs(seg.boundary.yAt(x + 0.5) - top));
        }

        // Obstacles: the other robot's feet point, if in view and visible.
        const Eigen::Vector3d otherFoot(world_->robotPose(1).x(), world_->robotPose(1).y(), 0.01);
        const auto footPx = sim::truePixel(*world_, 0, cam, otherFoot);
        // (The point itself lies under the robot's own feet: in view, not visible.)
        // In view: its feet and its knees, within 4 m.
        const auto kneePx = sim::truePixel(*world_, 0, cam, otherFoot + Eigen::Vector3d(0, 0, 0.25));
        auto onImage = [&](const std::optional<Eigen::Vector2d>& p) {
          return p && p->x() > 5 && p->x() < res.width - 5 && p->y() > 5 && p->y() < res.height - 5;
        };
        const bool inView = onImage(footPx) && onImage(kneePx) &&
                            (world_->robotPose(1).head<2>() - world_->robotPose(0).head<2>()).norm() < 4;
        bool found = false;
        for (const auto& o : seg.obstacles.obstacles) {
          const bool hit = footPx && footPx->x() >= o.left - 8 && footPx->x() <= o.right + 8 &&
                           footPx->y() >= o.top - 8 && footPx->y() <= o.bottom + 12;
          found = found || hit;
          // Anything else boxed: the goal posts and the robot's own feet are fine, the rest false.
          const Eigen::Vector2d footField = robotToField(o.footRobot, world_->robotPose(0));
          const bool nearGoal = std::abs(std::abs(footField.x()) - field.halfLength()) < 0.6 &&
                                std::abs(footField.y()) < field.dims.goalInnerWidth / 2 + 0.6;
          if (!hit && !nearGoal && (footField - world_->robotPose(1).head<2>()).norm() > 0.6) ++f.falseObstacles;
        }
        if (inView) f.robotsInView++, f.robotsFound += found;
        if (std::getenv("NAO_VISION_FRAMES"))
          std::printf("  frame %d %s: white %ld/%ld field %ld/%ld robot %d/%d\n", f.frames, cameraName(cam), f.whiteOnPaint - w0, f.white - w1, f.fieldOk - f0, f.fieldTruth - f1, found, inView);
        // NAO_VISION_IMAGES=<dir>: the annotated frames, to look at.
        if (const char* dir = std::getenv("NAO_VISION_IMAGES")) {
          cv::Mat vis = sim::rgbFromCameraImage(img);
          drawScanLineRegions(vis, seg.regions);
          drawFieldBoundary(vis, seg.boundary);
          drawObstacles(vis, seg.obstacles);
          for (const cv::Point& p : falseWhite) cv::circle(vis, p, 2, cv::Scalar(255, 0, 255), -1);
          char name[160];
          std::snprintf(name, sizeof name, "%s/%s_%02d_%s.png", dir, preset.c_str(), f.frames, cameraName(cam));
          sim::writePng(name, vis);
        }
      }
    }
    return f;
  }

  static sim::World* world_;
  static sim::CameraRenderer* renderer_;
  static std::vector<Pose> poses_;
};

sim::World* SimulatedVision::world_ = nullptr;
sim::CameraRenderer* SimulatedVision::renderer_ = nullptr;
std::vector<SimulatedVision::Pose> SimulatedVision::poses_;

TEST_F(SimulatedVision, LightingSweep) {
  std::map<std::string, Figures> all;
  std::printf("%-8s %7s %7s %9s %9s %9s %6s %9s\n", "preset", "field", "white", "bound.med", "bound.p90", "robots",
              "false", "top ms");
  for (const char* preset : {"default", "bright", "dark", "warm", "cold", "shadows", "noisy"}) {
    const Figures f = run(preset);
    std::vector<double> ms = f.ms;
    std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
    std::printf("%-8s %7.3f %7.3f %9.1f %9.1f %6d/%-2d %6d %9.2f\n", preset, f.field(), f.whitePrecision(),
                f.boundaryQuantile(0.5), f.boundaryQuantile(0.9), f.robotsFound, f.robotsInView, f.falseObstacles,
                ms.empty() ? 0.0 : ms[ms.size() / 2]);
    EXPECT_GT(f.fieldTruth, 10000) << preset;
    EXPECT_GE(f.field(), 0.97) << preset;
    EXPECT_GE(f.whitePrecision(), 0.9) << preset;
    EXPECT_GT(f.boundaryErr.size(), 50u) << preset;
    EXPECT_LE(f.boundaryQuantile(0.5), 2.0) << preset;
    EXPECT_LE(f.boundaryQuantile(0.9), 10.0) << preset;
    EXPECT_GE(f.obstacleRecall(), 0.75) << preset;
    EXPECT_LE(f.falseObstacles, f.frames / 4) << preset;
    all[preset] = f;
  }
  // Lighting independence: the field colour found does not depend on the light.
  double lo = 1, hi = 0;
  for (const auto& [name, f] : all) lo = std::min(lo, f.field()), hi = std::max(hi, f.field());
  std::printf("field coverage spread over the presets: %.3f\n", hi - lo);
  EXPECT_LE(hi - lo, 0.03);
}

}  // namespace
}  // namespace nao
