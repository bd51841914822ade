// A short simulated 1vs1 game (scenarios/Match.h) against the simulator's truth: the
// GameController's packets reach both robot programs, each walks to its READY position in its
// own half (the away robot's own frame is the field turned round), SET comes, the referee puts
// the four balls on the goal free-kick positions, and play starts; the same seed gives the
// same game (on 8 s: a minute of four rendered cameras costs 8 min of a core).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "scenarios/Match.h"

namespace {

nlohmann::json withoutWallTimes(nlohmann::json j) {
  j.erase("wall_s");
  j.erase("rtf");
  return j;
}

TEST(Match, TheGameControllersKickOffReachesBothRobots) {
  // The sanitizers' short version: INITIAL, then READY at 2 s; both robots hear it. The same
  // seed, the same game (JSON equal but for wall times).
  nao::sim::MatchOptions o;
  o.seconds = 8;
  const nao::sim::MatchResult r = nao::sim::runMatch(o);
  EXPECT_EQ(withoutWallTimes(nao::sim::runMatch(o).json), withoutWallTimes(r.json));
  EXPECT_EQ(r.state, "READY");
  int heard = 0;
  for (const auto& e : r.json["events"])
    if (e["kind"] == "robot_log" && e["text"] == "game: READY") ++heard;
  EXPECT_EQ(heard, 2) << r.json["events"].dump();
  // Each localizes at its start; the away robot's belief is in its own frame, the field turned round.
  for (const auto& robot : r.json["robots"]) {
    EXPECT_GE(robot["localization_error_m"].get<double>(), 0) << robot.dump();
    EXPECT_LT(robot["localization_error_m"].get<double>(), 0.1) << robot.dump();
  }
}

TEST(Match, BothRobotsGetReadyInTheirHalvesAndPlayStarts) {
  if (std::getenv("NAO_TEST_QUICK")) GTEST_SKIP() << "a game of 60 s: the Release stage runs it";
  nao::sim::MatchOptions o;
  o.seed = 3;
  o.seconds = 60;
  o.progress = [](double t, const std::string& status) { std::fprintf(stderr, "match: %.0f s %s\n", t, status.c_str()); };
  const nao::sim::MatchResult r = nao::sim::runMatch(o);
  const nlohmann::json& j = r.json;
  EXPECT_EQ(r.state, "PLAYING");
  std::map<std::string, double> stateAt;
  int ballsPlaced = 0;
  for (const auto& e : j["events"]) {
    if (e["kind"] == "gc_state" && !stateAt.count(e["text"])) stateAt[e["text"]] = e["t"];
    if (e["kind"] == "place" && e["what"] == "balls on the goal free-kick positions") ++ballsPlaced;
    EXPECT_NE(e["kind"], "fall") << e.dump();
  }
  ASSERT_TRUE(stateAt.count("READY") && stateAt.count("SET") && stateAt.count("PLAYING")) << j["events"].dump();
  EXPECT_NEAR(stateAt["READY"], 2, 0.05);
  EXPECT_LE(stateAt["SET"], stateAt["READY"] + 45.1);
  EXPECT_NEAR(stateAt["PLAYING"], stateAt["SET"] + 5, 0.05);
  EXPECT_EQ(ballsPlaced, 1);
  for (const auto& robot : j["robots"]) {
    EXPECT_GT(robot["distance_m"].get<double>(), 1.5) << robot.dump();  // from the side line towards (-+4.2, 0)
    EXPECT_GE(robot["localization_error_m"].get<double>(), 0) << robot.dump();
    EXPECT_LT(robot["localization_error_m"].get<double>(), 0.25) << robot.dump();
  }
  // Nobody crossed the halfway line or left the field on the way.
  for (const auto& e : j["events"])
    if (e["kind"] == "call") ADD_FAILURE() << e.dump();
}

}  // namespace
