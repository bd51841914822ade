// nao-soccer eval localization: the robot program's localization and ball model against the
// simulator's truth (scenarios/LocalizationEval.h), with --rows for evaluations that span
// sessions: one JSON line per trial, appended and flushed as the trial ends.
#include <cstdio>
#include <set>

#include "apps/Cli.h"
#include "apps/Commands.h"
#include "apps/Rows.h"
#include "apps/SimOptions.h"
#include "robot/Error.h"
#include "scenarios/EvalRows.h"
#include "scenarios/LocalizationEval.h"

namespace nao::cli {

namespace {

std::string fixed(const nlohmann::json& v, const char* format, double scale = 1) {
  if (v.is_null()) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, format, v.get<double>() * scale);
  return buf;
}

}  // namespace

int evalLocalizationCommand(const EvalLocalizationOptions& options) {
  sim::LocalizationEvalOptions o;
  o.field = fieldFrom(options.common);
  o.trials = options.trials;
  o.seed = options.common.seed;
  o.seeds = options.seeds;
  o.lightings = lightingsFrom(options.lighting);
  o.randomize = options.randomize;
  o.walkSeconds = options.seconds;
  o.kidnapEvery = options.kidnapEvery;
  o.rollEvery = options.rollEvery;
  o.oracle = options.percepts == "oracle";
  o.progress = [](const nlohmann::json& row, int done, int total) {
    const nlohmann::json one = sim::aggregateLocalizationRows(std::vector<nlohmann::json>{row});
    std::string extra;
    if (row.contains("kidnap"))
      extra = ", kidnap " + std::string(row["kidnap"]["recovered"].get<bool>() ? "recovered in " + fixed(row["kidnap"]["recovery_s"], "%.1f") + " s" : "NOT recovered");
    if (row.contains("rolling")) extra = ", rolling end error " + fixed(row["rolling"]["end_error_m"], "%.2f") + " m";
    std::fprintf(stderr,
                 "eval localization: trial %d/%d seed %llu (%s, %s): position median %s m p95 %s m, heading median %s "
                 "deg, valid %s %%, mirrored %s %%%s, %.0f s wall\n",
                 done, total, row.at("seed").get<unsigned long long>(), row.at("kind").get<std::string>().c_str(),
                 row.at("lighting").get<std::string>().c_str(), fixed(one["position_error_m"]["median"], "%.3f").c_str(),
                 fixed(one["position_error_m"]["p95"], "%.3f").c_str(), fixed(one["heading_error_deg"]["median"], "%.2f").c_str(),
                 fixed(one["valid_fraction"], "%.0f", 100).c_str(), fixed(one["mirrored_fraction"], "%.1f", 100).c_str(),
                 extra.c_str(), row.at("wall_s").get<double>());
  };
  DebugSink debug(options.debug);
  o.debug = debug.channels();
  std::vector<nlohmann::json> rows;
  if (!options.rows.empty()) {
    rows = readRows(options.rows, "eval localization");
    const auto mine = sim::trialSeeds(o.seed, o.trials, o.seeds, "--trials");
    const std::set<std::uint64_t> seeds(mine.begin(), mine.end());
    std::size_t others = 0;
    for (const auto& r : rows) others += !seeds.count(r.at("seed").get<std::uint64_t>());
    if (others > 0)
      std::fprintf(stderr, "eval localization: %s holds %zu rows of seeds outside this run's; they are not counted\n",
                   options.rows.c_str(), others);
  }
  RowWriter writeRow(options.rows);
  const nlohmann::json aggregate = sim::evalLocalization(o, rows, [&](const nlohmann::json& row) { writeRow(row); });
  nlohmann::json j = aggregate;
  j["seed"] = o.seed;
  if (!o.seeds.empty()) j["seed_list"] = o.seeds;
  nlohmann::json names = nlohmann::json::array();
  for (const auto& l : o.lightings) names.push_back(l.name);
  j["lighting"] = names;
  std::fprintf(stderr,
               "eval localization: %d trials: position median %s m p95 %s m max %s m; heading median %s deg p95 %s deg; "
               "mirrored %s; kidnap %d/%d recovered (median %s s); ball 0-2 m median %s m, 2-4 m %s m; rolling end "
               "median %s m; false balls %s\n",
               static_cast<int>(sim::trialSeeds(o.seed, o.trials, o.seeds, "--trials").size()), fixed(j["position_error_m"]["median"], "%.3f").c_str(), fixed(j["position_error_m"]["p95"], "%.3f").c_str(),
               fixed(j["position_error_m"]["max"], "%.3f").c_str(), fixed(j["heading_error_deg"]["median"], "%.2f").c_str(),
               fixed(j["heading_error_deg"]["p95"], "%.2f").c_str(), fixed(j["mirrored_fraction"], "%.4f").c_str(),
               j["kidnap"]["recovered"].get<int>(), j["kidnap"]["trials"].get<int>(),
               fixed(j["kidnap"]["recovery_s_median"], "%.1f").c_str(),
               fixed(j["ball"]["static_error_m"]["0-2"]["median"], "%.3f").c_str(),
               fixed(j["ball"]["static_error_m"]["2-4"]["median"], "%.3f").c_str(),
               fixed(j["ball"]["rolling_end_error_m"]["median"], "%.2f").c_str(),
               fixed(j["ball"]["false_ball_fraction"], "%.4f").c_str());
  if (!options.common.json.empty()) writeJson(options.common.json, j);
  return 0;
}

}  // namespace nao::cli
