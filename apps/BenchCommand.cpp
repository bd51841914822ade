// nao-soccer bench: speed figures as JSON. Medians, since these 2-core machines are noisy.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <numeric>
#include <random>
#include <sstream>

#include "apps/Cli.h"
#include "apps/Commands.h"
#include "apps/SimOptions.h"
#include "controllers/StandController.h"
#include "robot/Error.h"
#include "robot/Paths.h"
#include "scenarios/Match.h"
#include "scenarios/PerceptionBench.h"
#include "scenarios/SimRun.h"
#include "sim/CameraRenderer.h"
#include "sim/World.h"

namespace nao::cli {

namespace {

// Where a run's wall time went, as shares of it: rendering, cognition, motion, and the rest
// (physics, the backend, the images' hand-off).
std::map<std::string, double> wallShares(const sim::SimRunResult& r) {
  auto sum = [](const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / 1000; };
  const double wall = std::max(r.wallSeconds, 1e-9);
  const double render = sum(r.renderMsTop) + sum(r.renderMsBottom), cognition = sum(r.cognitionMs),
               motion = sum(r.motionMs);
  return {{"render", render / wall},
          {"cognition", cognition / wall},
          {"motion", motion / wall},
          {"physics_and_rest", 1 - (render + cognition + motion) / wall}};
}

}  // namespace

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
  o.venue = venueFrom(options.venue).forSeed(o.seed);
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
  std::vector<sim::RenderStages> stagesTop, stagesBottom;
  std::map<std::string, std::vector<double>> shares;
  std::string glVendor, glRenderer, glPlatform;
  for (int i = 0; i < repeats; ++i) {
    std::fprintf(stderr, "bench sim: camera run %d/%d\n", i + 1, repeats);
    const auto r = sim::runSim(o);
    cameraRtf.push_back(r.simSeconds / r.wallSeconds);
    top.insert(top.end(), r.renderMsTop.begin(), r.renderMsTop.end());
    stagesTop.insert(stagesTop.end(), r.renderStagesTop.begin(), r.renderStagesTop.end());
    stagesBottom.insert(stagesBottom.end(), r.renderStagesBottom.begin(), r.renderStagesBottom.end());
    for (const auto& [part, share] : wallShares(r)) shares[part].push_back(share);
    glVendor = r.glVendor;
    glRenderer = r.glRenderer;
    glPlatform = r.glPlatform;
    bottom.insert(bottom.end(), r.renderMsBottom.begin(), r.renderMsBottom.end());
  }
  nlohmann::json j = {{"physics_rtf", sim::median(physicsRtf)},
                            {"render_ms_top", sim::median(top)},
                            {"render_ms_bottom", sim::median(bottom)},
                            {"rtf_with_cameras", sim::median(cameraRtf)},
                            {"physics_rtf_runs", physicsRtf},
                            {"rtf_with_cameras_runs", cameraRtf},
                            {"renders", {{"top", top.size()}, {"bottom", bottom.size()}}},
                            {"simulated_seconds_per_run", {{"physics", seconds}, {"cameras", o.seconds}}},
                            {"lighting", lightingJson(lighting)},
                            {"venue", sim::toJson(o.venue)}};
  if (!glRenderer.empty()) {
    j["gl_vendor"] = glVendor;
    j["gl_renderer"] = glRenderer;
    j["gl_platform"] = glPlatform;
  }
  if (options.profile) {
    auto stages = [](const std::vector<sim::RenderStages>& v) {
      std::map<std::string, std::vector<double>> ms;
      for (const sim::RenderStages& s : v) {
        ms["scene"].push_back(s.scene);
        ms["draw"].push_back(s.draw);
        ms["read"].push_back(s.read);
        ms["sensor"].push_back(s.sensor);
      }
      nlohmann::json out = nlohmann::json::object();
      for (const auto& [k, x] : ms) out[k] = sim::median(x);
      return out;
    };
    j["profile"]["render_stage_ms_median"] = {{"top", stages(stagesTop)}, {"bottom", stages(stagesBottom)}};
    for (const auto& [part, v] : shares) j["profile"]["camera_run_wall_share"][part] = sim::median(v);
  }
  writeJson(options.common.json.empty() ? "-" : options.common.json, j);
  return 0;
}

namespace {

// The q-quantile (0..1) by nearest rank; 0 for none.
double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  return v[std::min(v.size() - 1, rank == 0 ? 0 : rank - 1)];
}

double round4(double x) { return std::round(x * 1e4) / 1e4; }

}  // namespace

// The robot program as `run --backend sim` runs it (both cameras at 30 Hz, the behaviour
// walking to --goto): ms per cognition run and per motion cycle, real-time factor. Each figure
// is taken per run; the median over the runs is reported.
int benchProgramCommand(const BenchProgramOptions& options) {
  const FieldDimensions field = fieldFrom(options.common);
  checkRobotModel(options.model, field);
  sim::SimRunOptions o;
  o.field = field;
  o.robotModel = options.model;
  o.seed = options.common.seed;
  o.lighting = lightingFrom(options.lighting);
  o.cameras = true;
  o.seconds = options.seconds;
  const auto& g = options.goTo;
  o.goTo = Pose2(g[0], g[1], g[2] * M_PI / 180);

  const char* keys[] = {"cognition_ms_median", "cognition_ms_p95",  "cognition_ms_top_median",
                        "cognition_ms_top_p95", "cognition_ms_bottom_median", "cognition_ms_bottom_p95",
                        "motion_ms_median",    "motion_ms_p95",     "motion_ms_p99",
                        "motion_ms_max",       "render_ms_top",     "render_ms_bottom",
                        "rtf"};
  std::map<std::string, std::vector<double>> figures;
  nlohmann::json runs = nlohmann::json::array();
  std::string glVendor, glRenderer, glPlatform;
  bool fell = false;
  for (int i = 0; i < options.repeats; ++i) {
    std::fprintf(stderr, "bench program: run %d/%d (%.0f simulated s)\n", i + 1, options.repeats, o.seconds);
    const sim::SimRunResult r = sim::runSim(o);
    glVendor = r.glVendor;
    glRenderer = r.glRenderer;
    glPlatform = r.glPlatform;
    const std::map<std::string, double> f = {{"cognition_ms_median", quantile(r.cognitionMs, 0.5)},
                                             {"cognition_ms_p95", quantile(r.cognitionMs, 0.95)},
                                             {"cognition_ms_top_median", quantile(r.cognitionMsTop, 0.5)},
                                             {"cognition_ms_top_p95", quantile(r.cognitionMsTop, 0.95)},
                                             {"cognition_ms_bottom_median", quantile(r.cognitionMsBottom, 0.5)},
                                             {"cognition_ms_bottom_p95", quantile(r.cognitionMsBottom, 0.95)},
                                             {"motion_ms_median", quantile(r.motionMs, 0.5)},
                                             {"motion_ms_p95", quantile(r.motionMs, 0.95)},
                                             {"motion_ms_p99", quantile(r.motionMs, 0.99)},
                                             {"motion_ms_max", quantile(r.motionMs, 1.0)},
                                             {"render_ms_top", quantile(r.renderMsTop, 0.5)},
                                             {"render_ms_bottom", quantile(r.renderMsBottom, 0.5)},
                                             {"rtf", r.wallSeconds > 0 ? r.simSeconds / r.wallSeconds : 0.0}};
    // Where the wall time went, as shares of the same run (robust to the machine's load).
    nlohmann::json run;
    for (const auto& [k, v] : wallShares(r)) {
      figures["wall_share_" + k].push_back(v);
      run["wall_share"][k] = round4(v);
    }
    for (const auto& [k, v] : f) {
      figures[k].push_back(v);
      run[k] = round4(v);
    }
    run["motion_cycles"] = r.motionMs.size();
    run["cognition_runs"] = {{"top", r.cognitionMsTop.size()}, {"bottom", r.cognitionMsBottom.size()}};
    run["fell"] = r.fell;
    run["walked_m"] = round4((r.finalPose.head<2>() - o.pose.head<2>()).norm());
    fell = fell || r.fell;
    runs.push_back(run);
  }
  nlohmann::json j;
  for (const char* k : keys) j[k] = round4(sim::median(figures[k]));
  for (const char* k : {"render", "cognition", "motion", "physics_and_rest"})
    j["wall_share"][k] = round4(sim::median(figures[std::string("wall_share_") + k]));
  j["repeats"] = options.repeats;
  j["simulated_seconds_per_run"] = o.seconds;
  j["goto"] = {g[0], g[1], g[2]};
  j["fell"] = fell;
  j["runs"] = runs;
  j["lighting"] = lightingJson(o.lighting);
  j["gl_vendor"] = glVendor;
  j["gl_renderer"] = glRenderer;
  j["gl_platform"] = glPlatform;

  if (options.perModule) {
    // One more run with the timing channel subscribed: each module's median ms per pipeline.
    std::fprintf(stderr, "bench program: per-module run (timing channel)\n");
    std::stringstream sink;
    DebugChannels debug(sink);
    debug.subscribe("timing");
    o.debug = &debug;
    sim::runSim(o);
    std::map<std::string, std::map<std::string, std::vector<double>>> ms;
    for (std::string line; std::getline(sink, line);) {
      const auto l = nlohmann::json::parse(line, nullptr, false);
      if (!l.is_object() || l.value("summary", false) || !l.contains("modules")) continue;
      const std::string pipeline = l.value("pipeline", "");
      for (const auto& m : l["modules"]) ms[pipeline][m.value("module", "")].push_back(m.value("ms", 0.0));
    }
    nlohmann::json modules = nlohmann::json::object();
    for (const auto& [pipeline, byModule] : ms)
      for (const auto& [module, v] : byModule) modules[pipeline][module] = round4(sim::median(v));
    j["module_ms_median"] = modules;
  }
  writeJson(options.common.json.empty() ? "-" : options.common.json, j);
  return 0;
}

// A short 1vs1 game, both robot programs, as `match` plays it: the real-time factor of the
// game's loop (setup apart) with both robots' four cameras rendered and seen by the vision, and
// with the fast percept mode; the modes take turns so that both see the same machine load, and
// the median ratio is reported.
int benchMatchCommand(const BenchMatchOptions& options) {
  sim::MatchOptions o;
  o.field = fieldFrom(options.common);
  o.lighting = lightingFrom(options.lighting);
  o.seed = options.common.seed;
  o.seconds = options.seconds;
  std::vector<std::string> modes;
  if (options.percepts != "oracle") modes.push_back("vision");
  if (options.percepts != "vision") modes.push_back("oracle");

  std::map<std::string, std::vector<double>> rtf;
  std::map<std::string, std::map<std::string, std::vector<double>>> shares;
  std::vector<double> ratios;
  nlohmann::json runs = nlohmann::json::array();
  std::string vendor, renderer, platform;
  for (int i = 0; i < options.repeats; ++i) {
    std::map<std::string, double> thisRound;
    for (const std::string& mode : modes) {
      std::fprintf(stderr, "bench match: %s game %d/%d (%.0f simulated s)\n", mode.c_str(), i + 1, options.repeats,
                   o.seconds);
      o.percepts = mode;
      const sim::MatchResult r = sim::runMatch(o);
      // The game's loop only: building the world and the programs (about 0.3 s) is no part of
      // how fast a game runs, and would weigh on short benches.
      const double wall = std::max(r.wallSeconds - r.wall.setup, 1e-9), factor = r.simSeconds / wall;
      rtf[mode].push_back(factor);
      thisRound[mode] = factor;
      const std::map<std::string, double> share = {
          {"physics", r.wall.physics / wall},
          {mode == "oracle" ? "oracle_views" : "render", r.wall.images / wall},
          {"cognition", r.wall.cognition / wall},
          {"motion", r.wall.motion / wall},
          {"referee_and_rest", 1 - (r.wall.physics + r.wall.images + r.wall.cognition + r.wall.motion) / wall}};
      nlohmann::json run = {{"percepts", mode}, {"rtf", round4(factor)}, {"simulated_s", round4(r.simSeconds)},
                            {"wall_s", round4(wall)}, {"setup_s", round4(r.wall.setup)}, {"state", r.state}};
      for (const auto& [k, v] : share) {
        shares[mode][k].push_back(v);
        run["wall_share"][k] = round4(v);
      }
      runs.push_back(run);
      if (!r.glRenderer.empty()) {
        vendor = r.glVendor;
        renderer = r.glRenderer;
        platform = r.glPlatform;
      }
    }
    if (thisRound.count("vision") && thisRound.count("oracle")) ratios.push_back(thisRound["oracle"] / thisRound["vision"]);
  }
  nlohmann::json j;
  for (const std::string& mode : modes) {
    j[mode == "vision" ? "rtf" : "rtf_oracle"] = round4(sim::median(rtf[mode]));
    for (const auto& [k, v] : shares[mode]) j["wall_share"][mode][k] = round4(sim::median(v));
  }
  if (!ratios.empty()) j["oracle_speedup"] = round4(sim::median(ratios));
  if (!renderer.empty()) {
    j["gl_vendor"] = vendor;
    j["gl_renderer"] = renderer;
    j["gl_platform"] = platform;
  }
  j["repeats"] = options.repeats;
  j["simulated_seconds_per_game"] = o.seconds;
  j["cameras"] = 4;
  j["runs"] = runs;
  j["lighting"] = lightingJson(o.lighting);
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
