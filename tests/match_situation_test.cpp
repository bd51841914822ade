// The referee in scripted situations (match --situation, scenarios/Situation.h): for each rule a
// situation of placed, scripted robots and kicked balls that must produce exactly its call (or
// point), and legal play that must produce none: 0 missed, 0 false. The situations lie in
// tests/situations/; the robots there are the referee's props (no robot program, no cameras).
// Then the file's checks: each problem named with its key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "robot/Error.h"
#include "scenarios/Match.h"

namespace {

namespace fs = std::filesystem;

struct Expected {
  const char* file;
  std::vector<std::string> calls;   // "rule team" (team "ball" for a ball's call), in order
  std::vector<std::string> points;  // "team how"
  std::vector<std::string> noPoints;  // "reason team"
  int falls = 0;                      // falls the referee saw
};

std::string situation(const char* name) { return std::string(NAO_SOURCE_DIR) + "/tests/situations/" + name; }

class Situations : public ::testing::TestWithParam<Expected> {};

TEST_P(Situations, ExactlyTheExpectedCalls) {
  const Expected& x = GetParam();
  nao::sim::MatchOptions o;
  o.situation = nao::sim::loadSituation(situation(x.file));
  const nao::sim::MatchResult r = nao::sim::runMatch(o);
  std::vector<std::string> calls, points, noPoints;
  int falls = 0;
  for (const auto& e : r.json["events"]) {
    falls += e["kind"] == "fall";
    const std::string team = e.contains("team") ? e["team"].get<std::string>() : "ball";
    if (e["kind"] == "call") calls.push_back(e["rule"].get<std::string>() + " " + team);
    if (e["kind"] == "point") points.push_back(team + " " + e["how"].get<std::string>());
    if (e["kind"] == "no_point") noPoints.push_back(e["reason"].get<std::string>() + " " + team);
  }
  EXPECT_EQ(calls, x.calls) << x.file << ": " << r.json["events"].dump();
  EXPECT_EQ(points, x.points) << x.file;
  EXPECT_EQ(noPoints, x.noPoints) << x.file;
  EXPECT_EQ(falls, x.falls) << x.file;
  EXPECT_NEAR(r.simSeconds, o.situation->seconds, 0.02);
}

INSTANTIATE_TEST_SUITE_P(
    Referee, Situations,
    ::testing::Values(Expected{"halfway_line.json", {"halfway_line home"}, {}, {}},
                      Expected{"leaving_the_field.json", {"leaving_the_field home"}, {}, {}},
                      Expected{"fallen_robot.json", {"fallen_robot away"}, {}, {}, 1},
                      Expected{"inactive_robot.json", {"inactive_robot home"}, {}, {}},
                      Expected{"illegal_position_in_set.json", {"illegal_position_in_set home"}, {}, {}},
                      Expected{"motion_in_set.json", {"motion_in_set home"}, {}, {}},
                      Expected{"goal.json", {}, {"home goal"}, {}},
                      Expected{"ball_in_half.json", {}, {"home ball_in_half"}, {}},
                      Expected{"intercepted.json", {}, {}, {"intercepted home"}},
                      Expected{"ball_out_side.json", {"ball_out_side ball"}, {}, {}},
                      // Two balls lying, one nudged at 1 s: 30 s without a ball touched or moved
                      // 0.5 m; balls played in their halves every 20 s, none across: a minute.
                      Expected{"game_stuck_no_change.json", {"global_game_stuck ball"}, {}, {}},
                      Expected{"game_stuck_no_crossing.json", {"global_game_stuck ball"}, {}, {}},
                      // A robot standing 0.2 m short of the halfway line, a fall with a get-up
                      // started at once, a slow ball still rolling in the own half: no call.
                      Expected{"legal_play.json", {}, {}, {}, 1},
                      // Standing still 11.5 s facing a ball (it lies in the top camera's view):
                      // looking at a ball is activity. inactive_robot.json has one behind it.
                      Expected{"looking_at_ball.json", {}, {}, {}}),
    [](const ::testing::TestParamInfo<Expected>& param) {
      std::string name = param.param.file;
      return name.substr(0, name.find('.'));
    });

TEST(SituationFile, EachProblemNamesItsKey) {
  const fs::path dir = fs::path(::testing::TempDir()) / "situation_files";
  fs::create_directories(dir);
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"{\"stat\": \"PLAYING\"}", "stat: unknown key"},
      {"{\"state\": \"HALFTIME\"}", "state: must be INITIAL, READY, SET or PLAYING"},
      {"{\"robots\": [{\"team\": \"home\", \"pose\": [0, 0]}]}", "robots[0].pose: must be 3 numbers"},
      {"{\"robots\": [{\"team\": \"visitors\", \"pose\": [0, 0, 0]}]}", "robots[0].team: must be home or away"},
      {"{\"robots\": [{\"team\": \"home\", \"pose\": [0, 0, 0], \"program\": true, \"script\": []}]}",
       "robots[0].script: a robot runs its program or a script, not both"},
      {"{\"robots\": [{\"team\": \"home\", \"pose\": [0, 0, 0], \"script\": [{\"t\": 1, \"do\": \"dance\"}]}]}",
       "robots[0].script[0].do: unknown action 'dance'"},
      {"{\"robots\": [{\"team\": \"home\", \"pose\": [0, 0, 0], \"script\": [{\"t\": 2, \"do\": \"stand\"}, {\"t\": 1, \"do\": \"sit\"}]}]}",
       "robots[0].script[1].t: steps must come in time order"},
      {"{\"balls\": [{\"position\": [0, 0], \"by\": \"home\"}]}", "balls[0].by: only with a velocity"},
      {"{\"seconds\": -1}", "seconds: must be in"},
      {"{\"robots\": [", "not JSON"}};
  for (const auto& [text, problem] : bad) {
    const std::string file = (dir / "s.json").string();
    std::ofstream(file) << text;
    try {
      nao::sim::loadSituation(file);
      ADD_FAILURE() << text << " was accepted";
    } catch (const nao::Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(file), std::string::npos) << what;
      EXPECT_NE(what.find(problem), std::string::npos) << text << ": " << what;
    }
  }
  // On the carpet: checked against the field when the situation runs.
  std::ofstream(dir / "far.json") << "{\"robots\": [{\"team\": \"home\", \"pose\": [6, 0, 0]}]}";
  nao::sim::MatchOptions o;
  o.situation = nao::sim::loadSituation((dir / "far.json").string());
  EXPECT_THROW(nao::sim::runMatch(o), nao::Error);
  fs::remove_all(dir);
}

}  // namespace
