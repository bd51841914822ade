#pragma once
// Many seeded 1vs1 games (scenarios/Match.h), our robot program at home: game i has the seed
// `seed + i`, and everything in it follows from that seed (the foreign robots with `randomize`,
// the camera noise, the coin toss), the lighting too (the seed's turn through the list). Each
// game becomes one row, so an interrupted evaluation resumes from its rows and a batch engine
// can split it by seeds; the aggregate is computed from the rows alone, sorted by seed.
#include <cstdint>
#include <functional>
#include <vector>

#include <nlohmann/json.hpp>

#include "scenarios/Match.h"

namespace nao::sim {

struct MatchEvalOptions {
  MatchOptions match;               // field, model, randomize, half length, opponent (seed and lighting per game)
  int games = 20;
  std::uint64_t seed = 1;
  std::vector<std::uint64_t> seeds;  // not empty: exactly these games (games and seed aside)
  std::vector<Lighting> lightings;  // game seed s uses lightings[s % size]
  std::function<void(const nlohmann::json& row, int done, int total)> progress;
};

// What every row of this evaluation carries: rows of other settings are refused.
nlohmann::json matchEvalSettings(const MatchEvalOptions& options);
// One game's row: `seed`, `settings`, `lighting`, `result` (win, draw, loss: home's), `score`,
// `points_by_kind`, `playing_s`, `calls` (team -> rule -> count), per team `falls` and
// `penalties`, `state`, `coin_toss`, `sim_s`, `wall_s`.
nlohmann::json matchRow(const MatchResult& game, std::uint64_t seed, const std::string& lighting, const nlohmann::json& settings);
// `games`, `wins`, `draws`, `losses`, `win_share`, `points_per_minute` (home's points over the
// minutes of PLAYING; `opponent_points_per_minute` the away's), `points_by_kind` (summed),
// `calls_by_rule` (team or "ball" -> rule -> count, summed), `games_with_call` (the same, games
// with at least one), `falls_per_game` (home's mean; `opponent_falls_per_game`), `per_game`
// (falls and penalties per team: mean, max), `unfinished` [seed] (games short of FINISHED).
nlohmann::json aggregateMatchRows(std::vector<nlohmann::json> rows);
// The evaluation: `rows` are those already done (their seeds are not run again), `onRow` gets
// each new row as it ends.
nlohmann::json evalMatch(const MatchEvalOptions& options, std::vector<nlohmann::json> rows = {},
                         const std::function<void(const nlohmann::json& row)>& onRow = {});

}  // namespace nao::sim
