// match: a simulated 1vs1 game (scenarios/Match.h), the game's JSON (docs: design.md) and a
// summary on stderr. eval match: many seeded games (scenarios/MatchEval.h), rows as they end.
#include <cstdio>
#include <filesystem>

#include "apps/Cli.h"
#include "apps/Commands.h"
#include "apps/Rows.h"
#include "apps/SimOptions.h"
#include "scenarios/Match.h"
#include "robot/OutputFiles.h"
#include "robot/Paths.h"
#include "scenarios/MatchEval.h"
#include "scenarios/MatchReplay.h"

namespace nao::cli {

int matchCommand(const MatchOptions& options) {
  sim::MatchOptions o;
  o.field = fieldFrom(options.common);
  o.robotModel = options.sim.model;
  o.venue = venueFrom(options.sim.venue).forSeed(options.common.seed);
  o.lighting = lightingFrom(options.sim.lighting);
  o.seed = options.common.seed;
  o.randomize = options.randomize;
  o.halfSeconds = options.halfSeconds;
  o.seconds = options.seconds;
  o.opponent = options.opponent;
  o.percepts = options.percepts;
  o.replay = !options.replay.empty();
  o.imagesDir = options.images;
  o.gc = options.gc;
  o.gcPort = static_cast<std::uint16_t>(options.gcPort);
  o.gcReturnPort = static_cast<std::uint16_t>(options.gcReturnPort);
  if (!options.situation.empty()) {
    o.situation = sim::loadSituation(options.situation, o.halfSeconds);
    if (!o.situation->field.empty() && !options.common.has("--field")) {
      // A field named in the situation file: relative to the data root unless it exists as given.
      const std::string given = o.situation->field;
      const std::string path = std::filesystem::exists(given) ? given : dataPath(given);
      o.field = FieldDimensions::load(path);
    }
    if (options.common.has("--seconds")) o.situation->seconds = options.seconds;
  }
  checkRobotModel(o.robotModel, o.field);
  o.progress = [](double t, const std::string& status) { std::fprintf(stderr, "match: %5.0f s simulated, %s\n", t, status.c_str()); };
  DebugSink debug(options.debug);
  o.debug = debug.channels();
  const sim::MatchResult r = sim::runMatch(o);
  std::fprintf(stderr, "match: %s, home %d : %d away after %.1f s simulated (%.1f s wall, %.2fx real time)\n",
               r.state.c_str(), r.homeScore, r.awayScore, r.simSeconds, r.wallSeconds,
               r.wallSeconds > 0 ? r.simSeconds / r.wallSeconds : 0.0);
  if (o.replay) io::writeFile(options.replay, sim::replayHtml(r.replay));
  writeJson(options.common.json.empty() ? "-" : options.common.json, r.json);
  return 0;
}

int evalMatchCommand(const EvalMatchOptions& options) {
  sim::MatchEvalOptions o;
  o.match.field = fieldFrom(options.common);
  o.match.robotModel = options.model;
  o.match.randomize = options.randomize;
  o.match.halfSeconds = options.halfSeconds;
  o.match.seconds = options.seconds;
  o.match.opponent = options.opponent;
  o.match.percepts = options.percepts;
  checkRobotModel(o.match.robotModel, o.match.field);
  o.games = options.games;
  o.seed = options.common.seed;
  o.seeds = options.seeds;
  o.lightings = lightingsFrom(options.lighting);
  o.match.progress = [](double t, const std::string& status) {
    if (static_cast<int>(t) % 60 < 10) std::fprintf(stderr, "eval match:   %5.0f s simulated, %s\n", t, status.c_str());
  };
  o.progress = [](const nlohmann::json& row, int done, int total) {
    std::fprintf(stderr, "eval match: game %d/%d seed %llu (%s): %s %d:%d, %s; %.0f s wall\n", done, total,
                 row.at("seed").get<unsigned long long>(), row.at("lighting").get<std::string>().c_str(),
                 row.at("result").get<std::string>().c_str(), row.at("score").at("home").get<int>(),
                 row.at("score").at("away").get<int>(), row.at("state").get<std::string>().c_str(), row.at("wall_s").get<double>());
  };
  std::vector<nlohmann::json> rows;
  if (!options.rows.empty()) rows = readRows(options.rows, "eval match");
  RowWriter writeRow(options.rows);
  nlohmann::json j = sim::evalMatch(o, rows, [&](const nlohmann::json& row) { writeRow(row); });
  j["seed"] = o.seed;
  if (!o.seeds.empty()) j["seed_list"] = o.seeds;
  std::fprintf(stderr, "eval match: %d games: %d won, %d drawn, %d lost; %.2f points per minute (opponent %.2f); %zu unfinished\n",
               j["games"].get<int>(), j["wins"].get<int>(), j["draws"].get<int>(), j["losses"].get<int>(),
               j["points_per_minute"].get<double>(), j["opponent_points_per_minute"].get<double>(), j["unfinished"].size());
  writeJson(options.common.json.empty() ? "-" : options.common.json, j);
  return 0;
}

}  // namespace nao::cli
