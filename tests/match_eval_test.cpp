// eval match (scenarios/MatchEval.h): the aggregate from rows alone (wins, draws, losses, points
// per minute of PLAYING, calls by rule), resuming from a rows file cut short to the same
// aggregate, rows of other settings refused; and the away robot's program chosen by --opponent:
// a configuration folder with a broken parameter file is refused naming the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "robot/Error.h"
#include "scenarios/MatchEval.h"

namespace {

using nao::sim::aggregateMatchRows;

nlohmann::json row(std::uint64_t seed, int home, int away, double playing, nlohmann::json calls = {{"home", nlohmann::json::object()}}) {
  return {{"seed", seed},
          {"settings", {{"x", 1}}},
          {"result", home > away ? "win" : home < away ? "loss" : "draw"},
          {"score", {{"home", home}, {"away", away}}},
          {"points_by_kind", {{"home", {{"goal", home}, {"ball_in_half", 0}}}, {"away", {{"goal", 0}, {"ball_in_half", away}}}}},
          {"playing_s", playing},
          {"calls", calls},
          {"robots", {{"home", {{"falls", 1}, {"penalties", 0}}}, {"away", {{"falls", 3}, {"penalties", 2}}}}},
          {"state", seed == 3 ? "PLAYING" : "FINISHED"}};
}

TEST(MatchEval, TheAggregateFromTheRows) {
  const nlohmann::json j = aggregateMatchRows(
      {row(2, 1, 1, 600), row(1, 4, 0, 600, {{"home", {{"inactive_robot", 2}}}, {"away", {{"halfway_line", 1}}}}), row(3, 0, 2, 300)});
  EXPECT_EQ(j["games"], 3);
  EXPECT_EQ(j["wins"], 1);
  EXPECT_EQ(j["draws"], 1);
  EXPECT_EQ(j["losses"], 1);
  EXPECT_NEAR(j["points_per_minute"].get<double>(), 5.0 / 25, 1e-12);  // 5 points in 1500 s
  EXPECT_NEAR(j["opponent_points_per_minute"].get<double>(), 3.0 / 25, 1e-12);
  EXPECT_EQ(j["points_by_kind"]["home"]["goal"], 5);
  EXPECT_EQ(j["points_by_kind"]["away"]["ball_in_half"], 3);
  EXPECT_EQ(j["calls_by_rule"]["home"]["inactive_robot"], 2);
  EXPECT_EQ(j["games_with_call"]["home"]["inactive_robot"], 1);
  EXPECT_EQ(j["calls_by_rule"]["away"]["halfway_line"], 1);
  EXPECT_NEAR(j["falls_per_game"].get<double>(), 1, 1e-12);
  EXPECT_NEAR(j["per_game"]["away"]["falls"]["mean"].get<double>(), 3, 1e-12);
  EXPECT_NEAR(j["per_game"]["away"]["penalties"]["max"].get<double>(), 2, 1e-12);
  EXPECT_EQ(j["unfinished"], nlohmann::json::array({3}));
}

// Two 3 s games (INITIAL, READY): rows written as they end; a second run with the last row cut
// in half runs that game again and agrees with the first.
TEST(MatchEval, RowsResumeToTheSameAggregateAndOtherSettingsAreRefused) {
  nao::sim::MatchEvalOptions o;
  o.games = 2;
  o.seed = 7;
  o.match.seconds = 3;
  o.match.opponent = "baseline";
  o.lightings = {nao::sim::Lighting{}};
  std::vector<nlohmann::json> rows;
  const nlohmann::json first = nao::sim::evalMatch(o, {}, [&](const nlohmann::json& r) { rows.push_back(r); });
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0]["seed"], 7);
  EXPECT_EQ(rows[1]["settings"]["opponent"], "baseline");
  EXPECT_EQ(first["games"], 2);
  EXPECT_EQ(first["draws"], 2);  // 0:0 before kick-off
  int ran = 0;
  const nlohmann::json again = nao::sim::evalMatch(o, {rows[0]}, [&](const nlohmann::json&) { ++ran; });
  EXPECT_EQ(ran, 1);
  EXPECT_EQ(again, first);
  nao::sim::MatchEvalOptions other = o;
  other.match.opponent = "self";
  EXPECT_THROW(nao::sim::evalMatch(other, rows), nao::Error);
}

TEST(MatchEval, AnOpponentFolderWithABrokenParameterFileIsRefusedByName) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / "match_opponent";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "parameters");
  std::filesystem::copy_file(std::filesystem::path(NAO_SOURCE_DIR) / "config/modules.json", dir / "modules.json");
  std::ofstream(dir / "parameters/BehaviorControl.json") << "{\"striker\": {\"player\": \"goalie\"}}";
  nao::sim::MatchOptions o;
  o.seconds = 1;
  o.opponent = dir.string();
  try {
    nao::sim::runMatch(o);
    ADD_FAILURE() << "a broken opponent configuration was accepted";
  } catch (const nao::Error& e) {
    EXPECT_NE(std::string(e.what()).find("BehaviorControl.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("player"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
