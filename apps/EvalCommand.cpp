// nao-soccer eval: accuracy against ground truth over many random cases. The first
// positional names what is evaluated (perception; calibration and walk join here).
#include <iostream>

#include "apps/Commands.h"
#include "apps/SimOptions.h"
#include "robot/Error.h"
#include "robot/Paths.h"
#include "scenarios/PerceptionEval.h"

namespace nao::cli {
namespace {

// --lighting: a preset, a key=value list, or "sweep" (every preset the sweep lists).
std::vector<sim::Lighting> lightingsFrom(const Args& args) {
  const std::string spec = args.str("lighting", "sweep");
  const std::string file = dataPath("config/lighting.json");
  if (spec == "sweep") return sim::Lighting::sweep(file);
  return {sim::Lighting::parse(spec, file)};
}

int evalPerception(const Args& args) {
  sim::PerceptionEvalOptions o;
  o.field = fieldFrom(args);
  o.trials = static_cast<int>(args.integer("trials", 300));
  if (o.trials < 1) throw Error("--trials", "must be positive");
  o.seed = args.seed();
  o.lightings = lightingsFrom(args);
  o.maxOffsetDeg = args.num("max-offset", 1.0);
  if (!(o.maxOffsetDeg >= 0 && o.maxOffsetDeg <= 10)) throw Error("--max-offset", "must be 0..10 deg");
  o.imagesDir = args.str("images", "");
  o.imagesEvery = static_cast<int>(args.integer("images-every", 25));
  o.failuresDir = args.str("failures", "");
  o.progress = [](int done, int total) { progress("eval perception", done, total); };
  const sim::PerceptionEvalResult r = sim::evaluatePerception(o);
  nlohmann::json j = r.toJson();
  j["trials"] = o.trials;
  j["seed"] = o.seed;
  j["max_offset_deg"] = o.maxOffsetDeg;
  nlohmann::json names = nlohmann::json::array();
  for (const auto& l : o.lightings) names.push_back(l.name);
  j["lighting"] = names;
  writeJson(args.str("json", "-"), j);
  return 0;
}

}  // namespace

int evalCalibration(const Args& args);  // apps/CalibrateCommand.cpp
int evalWalkCommand(const Args& args);    // apps/WalkCommand.cpp
int evalWalkToCommand(const Args& args);  // apps/WalkCommand.cpp
int evalGetUpCommand(const Args& args);   // apps/WalkCommand.cpp

int evalCommand(const Argv& argv) {
  auto options = commonOptions();
  options.insert(options.end(),
                 {{"trials", "N", "random scenes (default 300); perception renders each with both cameras"},
                  {"lighting", "SPEC", "sweep (default: every preset of the sweep), a preset, or a key=value list"},
                  {"max-offset", "DEG", "perception: injected camera offsets, uniform in +-DEG, told to the model (default 1)"},
                  {"solver", "gauss-newton|ceres", "calibration: the solver scored (default gauss-newton; the other is compared)"},
                  {"images", "DIR", "perception: write annotated frames to DIR"},
                  {"images-every", "N", "perception: annotate every N-th scene (default 25)"},
                  {"failures", "DIR", "perception: write annotated frames with a miss or a false detection to DIR"},
                  {"seconds", "S", "walk: seconds per trial (default 60); getup: time limit (default 15)"},
                  {"randomize", "", "walk, walk-to, getup: 'foreign' robots (masses +-5%, joint offsets +-1 deg, friction 0.6-1)"}});
  Args args("eval", argv, options, 1);
  if (args.helpRequested()) {
    std::cout << "usage: nao-soccer eval perception|calibration|walk|walk-to|getup [options]\n" << args.usage();
    return 0;
  }
  if (args.positional().empty()) throw Error("eval", "needs a target: perception, calibration, walk, walk-to or getup");
  const std::string target = args.positional()[0];
  if (target == "perception") return evalPerception(args);
  if (target == "calibration") return evalCalibration(args);
  if (target == "walk") return evalWalkCommand(args);
  if (target == "walk-to") return evalWalkToCommand(args);
  if (target == "getup") return evalGetUpCommand(args);
  throw Error(target, "unknown eval target (perception, calibration, walk, walk-to, getup)");
}

}  // namespace nao::cli
