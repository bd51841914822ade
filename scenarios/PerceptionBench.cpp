#include "scenarios/PerceptionBench.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "controllers/StandController.h"
#include "perception/CameraModel.h"
#include "perception/vision/CameraPipeline.h"
#include "robot/Error.h"
#include "robot/Paths.h"
#include "sim/CameraRenderer.h"
#include "sim/SceneBuilder.h"
#include "sim/World.h"

namespace nao::sim {
namespace {

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(q * v.size()));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

}  // namespace

nlohmann::json PerceptionBenchResult::toJson() const {
  return {{"total_ms_median", totalMsMedian},
          {"total_ms_p90", totalMsP90},
          {"total_ms_mean", totalMsMean},
          {"stages", stageMsMedian},
          {"frames", frames},
          {"image", {{"width", width}, {"height", height}}},
          {"threads", 1}};
}

PerceptionBenchResult benchPerception(const PerceptionBenchOptions& options) {
  if (options.frames < 1 || options.repeats < 1) throw Error("bench perception", "frames and repeats must be positive");
  SceneSpec spec;
  spec.field = options.field;
  spec.balls = {Eigen::Vector3d(0, 0, kBallRadius)};
  World world(spec, options.seed);
  CameraRenderer renderer(world.model());
  std::vector<Lighting> lightings = options.lightings;
  if (lightings.empty()) lightings.push_back(Lighting::parse("default", dataPath("config/lighting.json")));
  const FieldModel& field = world.field();
  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> uni(0, 1);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * uni(rng); };
  const CameraResolution res = world.cameraResolution(options.camera);
  const CameraIntrinsics in = CameraIntrinsics::fromFovY(res.width, res.height, world.cameraFovY());

  // 1. Render the scenes (random poses over the field, the head within its usual range).
  std::vector<CameraImage> images;
  std::vector<CameraMatrix> matrices;
  for (int f = 0; f < options.frames; ++f) {
    // Drawn theta, y, x: the order GCC gave the constructor's arguments before.
    const double theta = uniform(-M_PI, M_PI), y = uniform(-field.halfWidth(), field.halfWidth());
    const Eigen::Vector3d pose(uniform(-field.halfLength(), field.halfLength()), y, theta);
    JointArray posture = StandController::standPosture();
    posture[HeadYaw] = uniform(-100, 100) * M_PI / 180;
    posture[HeadPitch] = uniform(-15, 25) * M_PI / 180;
    world.placeRobot(0, pose, posture);
    const double bearing = pose.z() + posture[HeadYaw] + uniform(-30, 30) * M_PI / 180;
    const double dist = uniform(0.5, 5);
    world.placeBall(0, Eigen::Vector3d(pose.x() + dist * std::cos(bearing), pose.y() + dist * std::sin(bearing), kBallRadius));
    const SensorFrame s = world.sensors(0);
    matrices.push_back(computeCameraMatrix(s.joints.position, s.inertial.angle, options.camera, CameraCalibration{}, in));
    images.push_back(renderer.renderImage(world.model(), world.data(), world.cameraIndex(0, options.camera), res.width,
                                          res.height, lightings[f % lightings.size()], options.camera, 0, rng, ExposureWeights{}));
    if (options.progress) options.progress("render", f + 1, options.frames);
  }

  // 2. Time the vision (the camera pipeline, its modules timed one by one): one warm-up pass,
  // then `repeats` timed passes.
  CameraPipeline pipeline(options.camera, VisionGeometry{});
  for (int f = 0; f < std::min(20, options.frames); ++f) pipeline.process(images[f], matrices[f]);
  std::vector<std::vector<double>> total(options.frames);
  std::map<std::string, std::vector<std::vector<double>>> stages;
  for (int rep = 0; rep < options.repeats; ++rep) {
    for (int f = 0; f < options.frames; ++f) {
      pipeline.process(images[f], matrices[f]);
      total[f].push_back(pipeline.totalMs());
      for (const CameraPipeline::ModuleTime& t : pipeline.moduleMs()) {
        auto& v = stages[t.module];
        v.resize(options.frames);
        v[f].push_back(t.ms);
      }
    }
    if (options.progress) options.progress("perceive", rep + 1, options.repeats);
  }
  PerceptionBenchResult out;
  out.frames = options.frames;
  out.width = res.width;
  out.height = res.height;
  std::vector<double> perFrame;
  for (auto& t : total) perFrame.push_back(quantile(t, 0.5));
  out.totalMsMedian = quantile(perFrame, 0.5);
  out.totalMsP90 = quantile(perFrame, 0.9);
  double sum = 0;
  for (double v : perFrame) sum += v;
  out.totalMsMean = sum / perFrame.size();
  for (auto& [name, v] : stages) {
    std::vector<double> pf;
    for (auto& t : v) pf.push_back(quantile(t, 0.5));
    out.stageMsMedian[name] = quantile(pf, 0.5);
  }
  return out;
}

}  // namespace nao::sim
