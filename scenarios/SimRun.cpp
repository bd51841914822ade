#include "scenarios/SimRun.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <random>

#include <opencv2/imgcodecs.hpp>

#include "controllers/RobotProgram.h"
#include "controllers/StandController.h"
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

SimRunResult runSim(const SimRunOptions& options) {
  using Clock = std::chrono::steady_clock;
  SceneSpec spec;
  spec.field = options.field;
  spec.robots = {options.pose};
  spec.robotModel = options.robotModel;
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
    backend.setImageSource([&](CameraId cam, double time) {
      const auto t0 = Clock::now();
      const CameraResolution res = world.cameraResolution(cam);
      CameraImage img = renderer->renderImage(world.model(), world.data(), world.cameraIndex(0, cam), res.width,
                                              res.height, options.lighting, cam, time, noiseRng);
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
      (cam == CameraId::Top ? result.renderMsTop : result.renderMsBottom).push_back(ms);
      return img;
    });
  }

  // As on a NAO at start: the calibration stored for this robot's head (none: no offsets).
  RobotProgramConfig config;
  config.calibration = calibration::CalibrationStore().offsetsFor(backend.robotInfo().headId);
  config.headId = backend.robotInfo().headId;  // config/robots/<head id>/ overlays, if any
  config.field = options.field;
  config.debug = options.debug;
  RobotProgram program(config);
  result.moduleOrder = program.moduleOrder();
  const auto wallStart = Clock::now();
  const auto cycles = static_cast<std::uint64_t>(std::llround(options.seconds / kCycleTime));
  result.torsoHeightMin = result.torsoHeightMax = world.torsoPose(0).translation().z();
  int nextImageSecond = 0;
  for (std::uint64_t c = 0; c < cycles; ++c) {
    if (!program.cycle(backend)) break;
    ++result.cycles;
    const auto& images = program.blackboard().read<CameraImages>();
    for (CameraId cam : {CameraId::Top, CameraId::Bottom}) {
      const auto& img = images.latest[static_cast<int>(cam)];
      if (!img) continue;
      (cam == CameraId::Top ? result.imagesTop : result.imagesBottom)++;
      if (!options.imagesDir.empty() && world.time() + 1e-9 >= nextImageSecond) {
        char name[64];
        std::snprintf(name, sizeof name, "/%s_%03d.png", cameraName(cam), nextImageSecond);
        writePng(options.imagesDir + name, *img);
        result.imagesWritten.push_back(options.imagesDir + name);
        if (cam == CameraId::Bottom) ++nextImageSecond;
      }
    }
    const double z = world.torsoPose(0).translation().z();
    result.torsoHeightMin = std::min(result.torsoHeightMin, z);
    result.torsoHeightMax = std::max(result.torsoHeightMax, z);
    result.fell = result.fell || program.blackboard().read<FallState>().fallen;
    if (options.progress && c % 83 == 0) options.progress(world.time());
  }
  result.wallSeconds = std::chrono::duration<double>(Clock::now() - wallStart).count();
  result.imagesProcessedTop = program.cognitionRuns()[static_cast<int>(CameraId::Top)];
  result.imagesProcessedBottom = program.cognitionRuns()[static_cast<int>(CameraId::Bottom)];
  result.simSeconds = world.time();
  result.finalPose = world.robotPose(0);
  if (!options.imagesDir.empty()) {
    std::vector<Eigen::Vector3d> balls;
    for (int b = 0; b < world.ballCount(); ++b) balls.push_back(world.ballPosition(b));
    const std::string path = options.imagesDir + "/field.png";
    writePng(path, drawFieldView(world.field(), {result.finalPose}, balls));
    result.imagesWritten.push_back(path);
  }
  return result;
}

}  // namespace nao::sim
