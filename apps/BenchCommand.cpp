// nao-soccer bench: speed figures as JSON. Medians, since these 2-core machines are noisy.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <random>

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
namespace {

int benchSim(const Args& args) {
  const FieldDimensions field = fieldFrom(args);
  const sim::Lighting lighting = lightingFrom(args);
  const double seconds = args.num("seconds", 20);
  const int repeats = static_cast<int>(args.integer("repeats", 3));
  if (!(seconds > 0) || repeats < 1) throw Error("--seconds/--repeats", "must be positive");

  // Physics alone: the robot program standing, no cameras; the median of `repeats` runs.
  std::vector<double> physicsRtf, cameraRtf;
  sim::SimRunOptions o;
  o.field = field;
  o.robotModel = robotModelFrom(args);
  o.seed = args.seed();
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
  writeJson(args.str("json", "-"), j);
  return 0;
}

// The whole vision on simulated 640x480 top images (or --camera bottom), one core.
int benchPerception(const Args& args) {
  sim::PerceptionBenchOptions o;
  o.field = fieldFrom(args);
  o.seed = args.seed();
  o.frames = static_cast<int>(args.integer("frames", 300));
  o.repeats = static_cast<int>(args.integer("repeats", 3));
  if (o.frames < 1 || o.repeats < 1) throw Error("--frames/--repeats", "must be positive");
  const std::string spec = args.str("lighting", "default");
  o.lightings = spec == "sweep" ? sim::Lighting::sweep(dataPath("config/lighting.json"))
                                : std::vector<sim::Lighting>{lightingFrom(args)};
  const std::string cam = args.str("camera", "top");
  if (cam != "top" && cam != "bottom") throw Error("--camera", "must be top or bottom, not '" + cam + "'");
  o.camera = cam == "top" ? CameraId::Top : CameraId::Bottom;
  o.progress = [](const std::string& what, int done, int total) { progress("bench perception: " + what, done, total); };
  nlohmann::json j = sim::benchPerception(o).toJson();
  j["camera"] = cam;
  j["repeats"] = o.repeats;
  writeJson(args.str("json", "-"), j);
  return 0;
}

}  // namespace

int benchCalibration(const Args& args);  // apps/CalibrateCommand.cpp

int benchCommand(const Argv& argv) {
  auto options = commonOptions();
  for (auto& o : simOptions()) options.push_back(o);
  options.insert(options.end(), {{"seconds", "S", "simulated seconds per physics run (default 20)"},
                                 {"repeats", "N", "runs per figure; the median is reported (default 3)"},
                                 {"frames", "N", "perception: simulated frames (default 300)"},
                                 {"camera", "top|bottom", "perception: which camera (default top)"}});
  Args args("bench", argv, options, 1);
  if (args.helpRequested()) {
    std::cout << args.usage() << "  targets: sim, perception, calibration\n";
    return 0;
  }
  if (args.positional().empty()) throw Error("bench", "needs a target: sim, perception or calibration");
  const std::string target = args.positional()[0];
  if (target == "sim") return benchSim(args);
  if (target == "perception") return benchPerception(args);
  if (target == "calibration") return benchCalibration(args);
  throw Error(target, "unknown bench target (sim, perception, calibration)");
}

}  // namespace nao::cli
