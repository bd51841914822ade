// nao-soccer eval perception: the vision against the simulator's truth over many random scenes.
// The other eval targets live beside their commands (CalibrateCommand.cpp, WalkCommand.cpp).
#include "apps/Cli.h"
#include "apps/Commands.h"
#include "apps/SimOptions.h"
#include "controllers/RobotProgram.h"
#include "robot/OutputFiles.h"
#include "scenarios/PerceptionEval.h"

namespace nao::cli {

int evalPerceptionCommand(const EvalPerceptionOptions& options) {
  sim::PerceptionEvalOptions o;
  o.field = fieldFrom(options.common);
  o.trials = options.trials;
  o.seed = options.common.seed;
  o.lightings = lightingsFrom(options.lighting);
  o.venue = venueFrom(options.venue);
  o.maxOffsetDeg = options.maxOffset;
  o.imagesDir = options.images;
  o.imagesEvery = options.imagesEvery;
  o.failuresDir = options.failures;
  o.progress = [](int done, int total) { progress("eval perception", done, total); };
  o.percepts = options.percepts;
  o.oracle = loadParams<modules::OracleVision::Params>("OracleVision", RobotProgramConfig::defaultConfigDir());
  o.fitOracle = !options.fitOracle.empty();
  DebugSink debug(options.debug);
  o.debug = debug.channels();
  const sim::PerceptionEvalResult r = sim::evaluatePerception(o);
  nlohmann::json j = r.toJson();
  j["percepts"] = o.percepts;
  if (r.oracleFit) {
    // The command that fitted the model, so that the file says where its figures come from.
    char how[256];
    std::snprintf(how, sizeof how, "nao-soccer eval perception --trials %d --seed %llu --lighting %s --max-offset %g",
                  o.trials, static_cast<unsigned long long>(o.seed), options.lighting.c_str(), o.maxOffsetDeg);
    const auto fitted = r.oracleFit->params(o.oracle, how);
    io::writeFile(options.fitOracle, paramsToJson(fitted).dump(2) + "\n");
    j["oracle_fit"]["params"] = paramsToJson(fitted);
    j["oracle_fit"]["file"] = options.fitOracle;
  }
  j["trials"] = o.trials;
  j["seed"] = o.seed;
  j["max_offset_deg"] = o.maxOffsetDeg;
  nlohmann::json names = nlohmann::json::array();
  for (const auto& l : o.lightings) names.push_back(l.name);
  j["lighting"] = names;
  j["venue"] = venueJson(o.venue);
  writeJson(options.common.json.empty() ? "-" : options.common.json, j);
  return 0;
}

}  // namespace nao::cli
