#include "scenarios/SimRun.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <random>


#include "controllers/RobotProgram.h"
#include "controllers/StandController.h"
#include "perception/vision/Annotate.h"
#include "representations/perception/CameraPercepts.h"
#include "perception/calibration/CalibrationStore.h"
#include "robot/Error.h"
#include "robot/OutputFiles.h"
#include "sim/CameraRenderer.h"
#include "sim/FieldView.h"
#include "sim/ImageIO.h"
#include "sim/SimBackend.h"
#include "sim/World.h"

namespace nao::sim {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

namespace {

std::vector<Eigen::Vector3d> ballsOf(const World& world) {
  std::vector<Eigen::Vector3d> balls;
  for (int b = 0; b < world.ballCount(); ++b) balls.push_back(world.ballPosition(b));
  return balls;
}

// The belief drawn over the field view. ball: robot frame relative to the estimate.
EstimateOverlay overlayOf(const RobotPose& pose, const std::optional<BallModel>& ball) {
  EstimateOverlay o;
  if (pose.hypotheses > 0) {
    o.pose = Eigen::Vector3d(pose.pose.x, pose.pose.y, pose.pose.theta);
    o.positionCovariance = pose.covariance.topLeftCorner<2, 2>();
  }
  if (ball && ball->valid && pose.hypotheses > 0) o.ball = pose.pose * ball->position;
  return o;
}

}  // namespace

SimRunResult runSim(const SimRunOptions& options) {
  using Clock = std::chrono::steady_clock;
  SceneSpec spec;
  spec.field = options.field;
  spec.robots = {options.pose};
  if (options.ball) spec.balls = {Eigen::Vector3d(options.ball->x(), options.ball->y(), 0.05)};
  spec.robotModel = options.robotModel;
  spec.venue = options.venue;
  spec.venueSeed = options.seed;
  World world(spec, options.seed);
  world.setMiscalibration(0, options.miscalibration);
  world.placeRobot(0, options.pose, StandController::standPosture());

  SimRunResult result;
  if (!options.imagesDir.empty()) {
    io::makeDirectories(options.imagesDir);
  }

  std::unique_ptr<CameraRenderer> renderer;
  std::mt19937_64 noiseRng(options.seed ^ 0x9e3779b97f4a7c15ULL);
  SimBackend backend(world, 0, true);
  if (options.cameras) {
    renderer = std::make_unique<CameraRenderer>(world.model());
    backend.setImageSource([&](CameraId cam, double time, const ExposureWeights& metering) {
      const auto t0 = Clock::now();
      const CameraResolution res = world.cameraResolution(cam);
      CameraImage img = renderer->renderImage(world.model(), world.data(), world.cameraIndex(0, cam), res.width,
                                              res.height, options.lighting, cam, time, noiseRng, metering);
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
      (cam == CameraId::Top ? result.renderMsTop : result.renderMsBottom).push_back(ms);
      (cam == CameraId::Top ? result.renderStagesTop : result.renderStagesBottom).push_back(renderer->lastStages());
      return img;
    });
  }

  // As on a NAO at start: the calibration stored for this robot's head (none: no offsets).
  RobotProgramConfig config;
  config.calibration = calibration::CalibrationStore().offsetsFor(backend.robotInfo().headId);
  config.headId = backend.robotInfo().headId;  // config/robots/<head id>/ overlays, if any
  config.field = options.field;
  config.goTo = options.goTo;
  config.debug = options.debug;
  RobotProgram program(config);
  result.moduleOrder = program.moduleOrder();
  result.motionModules = program.pipeline().order();
  result.cognitionModules = program.cognitionPipeline().order();

  // The scorer: after each cognition run, the estimate against the truth (read here, never by
  // the robot program). The estimate belongs to its image's time; the odometry since then
  // moves it to now, as the behaviour would.
  const FieldModel fieldModel = FieldModel::from(options.field);
  auto estimateNow = [&](const Blackboard& cognition) {
    RobotPose pose = cognition.read<RobotPose>();
    const Pose2 odometryNow = program.blackboard().read<Odometry>().pose;
    pose.pose = pose.pose * (pose.odometry.inverse() * odometryNow);
    return pose;
  };
  auto headingError = [](double a, double b) { return std::abs(Pose2::wrap(a - b)); };
  auto trueBallRelative = [&]() -> std::optional<Eigen::Vector2d> {
    if (world.ballCount() == 0) return std::nullopt;
    const Eigen::Vector3d r = world.robotPose(0), b = world.ballPosition(0);
    return Pose2(r.x(), r.y(), r.z()).inverse() * Eigen::Vector2d(b.x(), b.y());
  };
  // The ball model belongs to its image's time too: moved to now by the odometry.
  auto ballNow = [&](const Blackboard& cognition) {
    BallModel ball = cognition.read<BallModel>();
    const Pose2 delta = cognition.read<RobotPose>().odometry.inverse() * program.blackboard().read<Odometry>().pose;
    ball.position = delta.inverse() * ball.position;
    return ball;
  };
  const bool modeling = program.cognitionPipeline().order().end() !=
                        std::find(program.cognitionPipeline().order().begin(), program.cognitionPipeline().order().end(),
                                  std::string("SelfLocalization"));
  const bool ballModeling = modeling && std::find(result.cognitionModules.begin(), result.cognitionModules.end(),
                                                  std::string("BallLocator")) != result.cognitionModules.end();
  std::optional<CameraPercepts> percepts[kNumCameras];
  program.setCognitionObserver([&](const CameraImage& image, const Blackboard& cognition) {
    ++result.cognitionRunsTotal;
    if (!options.imagesDir.empty() && cognition.has<CameraPercepts>())
      percepts[static_cast<int>(image.camera)] = cognition.read<CameraPercepts>();
    if (!modeling || world.time() < 2.0) return;
    const RobotPose pose = estimateNow(cognition);
    if (!pose.valid) return;
    ++result.validRuns;
    const Eigen::Vector3d truth = world.robotPose(0);
    result.positionErrors.push_back((pose.pose.translation() - truth.head<2>()).norm());
    result.headingErrors.push_back(headingError(pose.pose.theta, truth.z()));
    if (ballModeling) {
      const BallModel ball = ballNow(cognition);
      if (const auto rel = trueBallRelative(); rel && ball.valid && !ball.lost)
        result.ballErrors.push_back((ball.position - *rel).norm());
    }
  });
  const auto wallStart = Clock::now();
  const auto cycles = static_cast<std::uint64_t>(std::llround(options.seconds / kCycleTime));
  result.torsoHeightMin = result.torsoHeightMax = world.torsoPose(0).translation().z();
  int nextImageSecond = 0, nextSecond = 1;
  for (std::uint64_t c = 0; c < cycles; ++c) {
    if (!program.cycle(backend)) break;
    ++result.cycles;
    result.motionMs.push_back(program.lastTiming().motionMs);
    for (double ms : program.lastTiming().cognitionMs) result.cognitionMs.push_back(ms);
    {  // RobotProgram::cycle runs cognition once per image present, top first
      const auto& latest = program.blackboard().read<CameraImages>().latest;
      const auto& ms = program.lastTiming().cognitionMs;
      std::size_t k = 0;
      for (CameraId cam : {CameraId::Top, CameraId::Bottom})
        if (latest[static_cast<int>(cam)] && k < ms.size())
          (cam == CameraId::Top ? result.cognitionMsTop : result.cognitionMsBottom).push_back(ms[k++]);
    }
    if (modeling && program.cognitionBoard().has<RobotPose>() && world.time() + 1e-9 >= nextSecond) {
      SimRunSecond second;
      second.t = world.time();
      second.truePose = world.robotPose(0);
      second.estimate = estimateNow(program.cognitionBoard());
      if (second.estimate.valid) {
        second.positionError = (second.estimate.pose.translation() - second.truePose.head<2>()).norm();
        second.headingError = headingError(second.estimate.pose.theta, second.truePose.z());
      }
      if (world.ballCount() > 0) second.trueBall = world.ballPosition(0).head<2>();
      if (ballModeling) {
        second.ball = ballNow(program.cognitionBoard());
        if (const auto rel = trueBallRelative(); rel && second.ball.valid) second.ballError = (second.ball.position - *rel).norm();
      }
      result.seconds.push_back(second);
      ++nextSecond;
    }
    const auto& images = program.blackboard().read<CameraImages>();
    for (CameraId cam : {CameraId::Top, CameraId::Bottom}) {
      const auto& img = images.latest[static_cast<int>(cam)];
      if (!img) continue;
      (cam == CameraId::Top ? result.imagesTop : result.imagesBottom)++;
      if (!options.imagesDir.empty() && world.time() + 1e-9 >= nextImageSecond) {
        char name[64];
        std::snprintf(name, sizeof name, "/%s_%03d.png", cameraName(cam), nextImageSecond);
        const auto& p = percepts[static_cast<int>(cam)];
        if (p && p->processed && p->timestamp == img->timestamp) {
          VisionResult shown;
          shown.boundary = p->fieldBoundary;
          shown.obstacles = p->obstacles;
          shown.lines = p->linesPercept();
          shown.ball = p->ball;
          shown.penaltyMarkImage = p->penaltyMarkImage;
          writePng(options.imagesDir + name, annotateVision(rgbFromCameraImage(*img), shown, p->cameraMatrix));
        } else {
          writePng(options.imagesDir + name, *img);
        }
        result.imagesWritten.push_back(options.imagesDir + name);
        if (cam == CameraId::Bottom) {
          std::snprintf(name, sizeof name, "/field_%03d.png", nextImageSecond);
          cv::Mat view = drawFieldView(fieldModel, {world.robotPose(0)}, ballsOf(world));
          if (modeling && program.cognitionBoard().has<RobotPose>()) drawEstimates(view, fieldModel, overlayOf(estimateNow(program.cognitionBoard()),
                                                                 ballModeling ? std::optional(ballNow(program.cognitionBoard())) : std::nullopt));
          writePng(options.imagesDir + name, view);
          result.imagesWritten.push_back(options.imagesDir + name);
          ++nextImageSecond;
        }
      }
    }
    const double z = world.torsoPose(0).translation().z();
    result.torsoHeightMin = std::min(result.torsoHeightMin, z);
    result.torsoHeightMax = std::max(result.torsoHeightMax, z);
    result.fell = result.fell || program.blackboard().read<FallState>().fallen;
    if (options.progress && c % 83 == 0) options.progress(world.time());
  }
  result.wallSeconds = std::chrono::duration<double>(Clock::now() - wallStart).count();
  if (renderer) {
    result.glVendor = renderer->glVendor();
    result.glRenderer = renderer->glRenderer();
    result.glPlatform = renderer->glPlatform();
  }
  result.imagesProcessedTop = program.cognitionRuns()[static_cast<int>(CameraId::Top)];
  result.imagesProcessedBottom = program.cognitionRuns()[static_cast<int>(CameraId::Bottom)];
  result.simSeconds = world.time();
  result.finalPose = world.robotPose(0);
  const bool estimated = program.cognitionBoard().has<RobotPose>();
  if (modeling && estimated) result.finalEstimate = estimateNow(program.cognitionBoard());
  if (ballModeling && estimated) result.finalBall = ballNow(program.cognitionBoard());
  if (!options.imagesDir.empty()) {
    const std::string path = options.imagesDir + "/field.png";
    cv::Mat view = drawFieldView(world.field(), {result.finalPose}, ballsOf(world));
    if (modeling && estimated)
      drawEstimates(view, fieldModel,
                    overlayOf(result.finalEstimate, ballModeling ? std::optional(result.finalBall) : std::nullopt));
    writePng(path, view);
    result.imagesWritten.push_back(path);
  }
  return result;
}

}  // namespace nao::sim
