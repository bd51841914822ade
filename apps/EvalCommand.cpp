// nao-soccer eval perception: the vision against the simulator's truth over many random scenes.
// The other eval targets live beside their commands (CalibrateCommand.cpp, WalkCommand.cpp).
#include "apps/Cli.h"
#include "apps/Commands.h"
#include "apps/SimOptions.h"
#include "scenarios/PerceptionEval.h"

namespace nao::cli {

int evalPerceptionCommand(const EvalPerceptionOptions& options) {
  sim::PerceptionEvalOptions o;
  o.field = fieldFrom(options.common);
  o.trials = options.trials;
  o.seed = options.common.seed;
  o.lightings = lightingsFrom(options.lighting);
  o.maxOffsetDeg = options.maxOffset;
  o.imagesDir = options.images;
  o.imagesEvery = options.imagesEvery;
  o.failuresDir = options.failures;
  o.progress = [](int done, int total) { progress("eval perception", done, total); };
  DebugSink debug(options.debug);
  o.debug = debug.channels();
  const sim::PerceptionEvalResult r = sim::evaluatePerception(o);
  nlohmann::json j = r.toJson();
  j["trials"] = o.trials;
  j["seed"] = o.seed;
  j["max_offset_deg"] = o.maxOffsetDeg;
  nlohmann::json names = nlohmann::json::array();
  for (const auto& l : o.lightings) names.push_back(l.name);
  j["lighting"] = names;
  writeJson(options.common.json.empty() ? "-" : options.common.json, j);
  return 0;
}

}  // namespace nao::cli
