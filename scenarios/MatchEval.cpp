#include "scenarios/MatchEval.h"

#include <algorithm>
#include <array>
#include <map>

#include "robot/Error.h"
#include "scenarios/EvalRows.h"

namespace nao::sim {

namespace {

const char* kTeams[2] = {"home", "away"};

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

// table[who][rule] += n, the entries made as needed.
void add(nlohmann::json& table, const std::string& who, const std::string& rule, int n) {
  nlohmann::json& row = table[who];
  if (!row.is_object()) row = nlohmann::json::object();
  row[rule] = row.value(rule, 0) + n;
}

}  // namespace

nlohmann::json matchEvalSettings(const MatchEvalOptions& o) {
  nlohmann::json lightings = nlohmann::json::array();
  for (const Lighting& l : o.lightings) lightings.push_back(l.name);
  return {{"randomize", o.match.randomize},
          {"half_s", o.match.halfSeconds},
          {"seconds", o.match.seconds},
          {"opponent", o.match.opponent},
          {"percepts", o.match.percepts},
          {"lightings", lightings},
          {"robot_model", o.match.robotModel},
          {"field", {{"length", o.match.field.length}, {"width", o.match.field.width}}}};
}

nlohmann::json matchRow(const MatchResult& game, std::uint64_t seed, const std::string& lighting, const nlohmann::json& settings) {
  const nlohmann::json& j = game.json;
  nlohmann::json calls = {{"home", nlohmann::json::object()}, {"away", nlohmann::json::object()}, {"ball", nlohmann::json::object()}};
  for (const auto& e : j.at("events")) {
    if (e.value("kind", "") != "call") continue;
    const std::string who = e.contains("team") ? e["team"].get<std::string>() : "ball";
    const std::string rule = e.at("rule").get<std::string>();
    calls[who][rule] = calls[who].value(rule, 0) + 1;
  }
  const int home = game.homeScore, away = game.awayScore;
  nlohmann::json row = {{"seed", seed},
                        {"settings", settings},
                        {"lighting", lighting},
                        {"result", home > away ? "win" : home < away ? "loss" : "draw"},
                        {"winner", j.at("winner")},
                        {"coin_toss", j.value("coin_toss", false)},
                        {"score", j.at("score")},
                        {"points_by_kind", j.at("points_by_kind")},
                        {"playing_s", j.at("playing_s")},
                        {"calls", calls},
                        {"state", game.state},
                        {"sim_s", game.simSeconds},
                        {"wall_s", game.wallSeconds}};
  for (const auto& r : j.at("robots"))
    row["robots"][r.at("team").get<std::string>()] = {{"falls", r.at("falls")},
                                                      {"penalties", r.at("penalties")},
                                                      {"distance_m", r.at("distance_m")},
                                                      {"localization_error_m", r.at("localization_error_m")}};
  return row;
}

nlohmann::json aggregateMatchRows(std::vector<nlohmann::json> rows) {
  std::sort(rows.begin(), rows.end(),
            [](const nlohmann::json& a, const nlohmann::json& b) { return a.at("seed").get<std::uint64_t>() < b.at("seed").get<std::uint64_t>(); });
  int wins = 0, draws = 0, losses = 0;
  double playing = 0;
  std::array<double, 2> points{};
  nlohmann::json byKind = {{"home", {{"goal", 0}, {"ball_in_half", 0}}}, {"away", {{"goal", 0}, {"ball_in_half", 0}}}};
  nlohmann::json calls = nlohmann::json::object(), gamesWithCall = nlohmann::json::object();
  std::map<std::string, std::vector<double>> falls, penalties;
  nlohmann::json unfinished = nlohmann::json::array();
  for (const auto& r : rows) {
    const std::string result = r.at("result");
    wins += result == "win";
    draws += result == "draw";
    losses += result == "loss";
    playing += r.at("playing_s").get<double>();
    for (int t = 0; t < 2; ++t) {
      const std::string team = kTeams[t];
      points[static_cast<std::size_t>(t)] += r.at("score").at(team).get<double>();
      for (const char* kind : {"goal", "ball_in_half"})
        byKind[team][kind] = byKind[team][kind].get<int>() + r.at("points_by_kind").at(team).at(kind).get<int>();
      falls[team].push_back(r.at("robots").at(team).at("falls").get<double>());
      penalties[team].push_back(r.at("robots").at(team).at("penalties").get<double>());
    }
    for (const auto& [who, rules] : r.at("calls").items())
      for (const auto& [rule, n] : rules.items()) {
        add(calls, who, rule, n.get<int>());
        add(gamesWithCall, who, rule, 1);
      }
    if (r.at("state") != "FINISHED") unfinished.push_back(r.at("seed"));
  }
  const double minutes = playing / 60;
  nlohmann::json perGame = nlohmann::json::object();
  for (const char* team : kTeams)
    perGame[team] = {{"falls", {{"mean", mean(falls[team])}, {"max", falls[team].empty() ? 0.0 : *std::max_element(falls[team].begin(), falls[team].end())}}},
                     {"penalties", {{"mean", mean(penalties[team])}, {"max", penalties[team].empty() ? 0.0 : *std::max_element(penalties[team].begin(), penalties[team].end())}}}};
  const int games = static_cast<int>(rows.size());
  return {{"games", games},
          {"wins", wins},
          {"draws", draws},
          {"losses", losses},
          {"win_share", games > 0 ? static_cast<double>(wins) / games : 0.0},
          {"points_per_minute", minutes > 0 ? points[0] / minutes : 0.0},
          {"opponent_points_per_minute", minutes > 0 ? points[1] / minutes : 0.0},
          {"playing_min", minutes},
          {"points_by_kind", byKind},
          {"calls_by_rule", calls},
          {"games_with_call", gamesWithCall},
          {"falls_per_game", mean(falls["home"])},
          {"opponent_falls_per_game", mean(falls["away"])},
          {"per_game", perGame},
          {"unfinished", unfinished}};
}

nlohmann::json evalMatch(const MatchEvalOptions& o, std::vector<nlohmann::json> rows,
                         const std::function<void(const nlohmann::json& row)>& onRow) {
  const std::vector<std::uint64_t> seeds = trialSeeds(o.seed, o.games, o.seeds, "--games");
  if (o.lightings.empty()) throw Error("--lighting", "no lighting");
  const nlohmann::json settings = matchEvalSettings(o);
  const auto play = [&](std::uint64_t seed) {
    MatchOptions m = o.match;
    m.seed = seed;
    m.lighting = o.lightings[seed % o.lightings.size()];
    return matchRow(runMatch(m), seed, m.lighting.name, settings);
  };
  nlohmann::json j = aggregateMatchRows(collectRows(seeds, rowsBySeed(std::move(rows), settings), play, onRow, o.progress));
  j["settings"] = settings;
  return j;
}

}  // namespace nao::sim
