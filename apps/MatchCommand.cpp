// match: a simulated 1vs1 game (scenarios/Match.h), the game's JSON (docs: design.md) and a
// summary on stderr.
#include <cstdio>

#include "apps/Cli.h"
#include "apps/Commands.h"
#include "apps/SimOptions.h"
#include "scenarios/Match.h"

namespace nao::cli {

int matchCommand(const MatchOptions& options) {
  sim::MatchOptions o;
  o.field = fieldFrom(options.common);
  o.robotModel = options.sim.model;
  o.lighting = lightingFrom(options.sim.lighting);
  o.seed = options.common.seed;
  o.randomize = options.randomize;
  o.halfSeconds = options.halfSeconds;
  o.seconds = options.seconds;
  checkRobotModel(o.robotModel, o.field);
  o.progress = [](double t, const std::string& status) { std::fprintf(stderr, "match: %5.0f s simulated, %s\n", t, status.c_str()); };
  const sim::MatchResult r = sim::runMatch(o);
  std::fprintf(stderr, "match: %s, home %d : %d away after %.1f s simulated (%.1f s wall, %.2fx real time)\n",
               r.state.c_str(), r.homeScore, r.awayScore, r.simSeconds, r.wallSeconds,
               r.wallSeconds > 0 ? r.simSeconds / r.wallSeconds : 0.0);
  writeJson(options.common.json.empty() ? "-" : options.common.json, r.json);
  return 0;
}

}  // namespace nao::cli
