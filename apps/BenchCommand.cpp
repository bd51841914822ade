// nao-soccer bench: speed figures as JSON. Medians, since these 2-core machines are noisy.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <random>

#include "apps/Cli.h"
#include "apps/Commands.h"
#include "apps/SimOptions.h"
#include "controllers/StandController.h"
#include "robot/Error.h"
#include "robot/Paths.h"
#include "scenarios/PerceptionBench.h"
#include "scenarios/SimRun.h"
#include "sim/CameraRenderer.h"
#include "sim/World.h"

namespace nao::cli {

int benchSimCommand(const BenchSimOptions& options) {
  const FieldDimensions field = fieldFrom(options.common);
  const sim::Lighting lighting = lightingFrom(options.lighting);
  const double seconds = options.seconds;
  const int repeats = options.repeats;
  checkRobotModel(options.model, field);

  // Physics alone: the robot program standing, no cameras; the median of `repeats` runs.
  std::vector<double> physicsRtf, cameraRtf;
  sim::SimRunOptions o;
  o.field = field;
  o.robotModel = options.model;
  o.seed = options.common.seed;
  o.lighting = lighting;
  o.cameras = false;
  o.seconds = seconds;
  for (int i = 0; i < repeats; ++i) {
    std::fprintf(stderr, "bench sim: physics run %d/%d\n", i + 1, repeats);
    const auto r = sim::runSim(o);
    physicsRtf.push_back(r.simSeconds / r.wallSeconds);
  }
  // Both cameras at 30 Hz.
  o.cameras = true;
  o.seconds = std::min(seconds, 10.0);
  std::vector<double> top, bottom;
  for (int i = 0; i < repeats; ++i) {
    std::fprintf(stderr, "bench sim: camera run %d/%d\n", i + 1, repeats);
    const auto r = sim::runSim(o);
    cameraRtf.push_back(r.simSeconds / r.wallSeconds);
    top.insert(top.end(), r.renderMsTop.begin(), r.renderMsTop.end());
    bottom.insert(bottom.end(), r.renderMsBottom.begin(), r.renderMsBottom.end());
  }
  const nlohmann::json j = {{"physics_rtf", sim::median(physicsRtf)},
                            {"render_ms_top", sim::median(top)},
                            {"render_ms_bottom", sim::median(bottom)},
                            {"rtf_with_cameras", sim::median(cameraRtf)},
                            {"physics_rtf_runs", physicsRtf},
                            {"rtf_with_cameras_runs", cameraRtf},
                            {"renders", {{"top", top.size()}, {"bottom", bottom.size()}}},
                            {"simulated_seconds_per_run", {{"physics", seconds}, {"cameras", o.seconds}}},
                            {"lighting", lightingJson(lighting)}};
  writeJson(options.common.json.empty() ? "-" : options.common.json, j);
  return 0;
}

// The whole vision on simulated 640x480 top images (or --camera bottom), one core.
int benchPerceptionCommand(const BenchPerceptionOptions& options) {
  sim::PerceptionBenchOptions o;
  o.field = fieldFrom(options.common);
  o.seed = options.common.seed;
  o.frames = options.frames;
  o.repeats = options.repeats;
  o.lightings = lightingsFrom(options.lighting);
  const std::string& cam = options.camera;
  o.camera = cam == "top" ? CameraId::Top : CameraId::Bottom;
  o.progress = [](const std::string& what, int done, int total) { progress("bench perception: " + what, done, total); };
  nlohmann::json j = sim::benchPerception(o).toJson();
  j["camera"] = cam;
  j["repeats"] = o.repeats;
  writeJson(options.common.json.empty() ? "-" : options.common.json, j);
  return 0;
}

}  // namespace nao::cli
