// --debug CHANNEL[,CHANNEL] on the commands (robot/Debug.h): `timing` names every module of the
// robot program, walk_trace carries the walk's real steps, an unknown channel is refused before
// the run, and with the default sink (stderr) stdout still carries only the JSON; `match --debug`
// traces the home robot's behaviour: its striker's state, the ball it chose and its pose.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/RunCommand.h"

namespace {

namespace fs = std::filesystem;
using nao::test::runCommand;

std::string tempPath(const std::string& name) { return (fs::path(::testing::TempDir()) / ("debug_" + name)).string(); }

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

// Every line of `path` as JSON (a line that is not JSON fails the test); onlyDebug: only the
// lines that start as debug lines do (stderr carries the command's log lines too).
std::vector<nlohmann::json> jsonLines(const std::string& path, bool onlyDebug = false) {
  std::vector<nlohmann::json> out;
  std::istringstream in(slurp(path));
  for (std::string line; std::getline(in, line);) {
    if (onlyDebug && line.rfind("{\"channel\":", 0) != 0) continue;
    auto j = nlohmann::json::parse(line, nullptr, false);
    EXPECT_TRUE(j.is_object()) << "not a JSON object: " << line;
    if (j.is_object()) out.push_back(std::move(j));
  }
  return out;
}

TEST(DebugChannels, RunTimingNamesEveryModuleOfTheProgram) {
  const std::string lines = tempPath("timing.jsonl"), json = tempPath("run.json");
  const auto r = runCommand("run --backend sim --seconds 1 --cameras off --debug timing --debug-out " + lines +
                            " --json " + json, 300);
  ASSERT_TRUE(r.code == 0 || r.code == 1) << r.out;  // 1: a fall, still a run
  EXPECT_EQ(r.out.find("\"channel\""), std::string::npos) << "debug lines went to the file only:\n" << r.out;
  const auto run = nlohmann::json::parse(slurp(json));
  const auto all = jsonLines(lines);
  std::set<std::string> named;
  int motionRuns = 0;
  long summaryRuns = -1;
  double lastT = -1;
  for (const auto& j : all) {
    EXPECT_EQ(j.at("channel"), "timing");
    for (const auto& m : j.at("modules")) {
      named.insert(m.at("module").get<std::string>());
      EXPECT_TRUE(m.at("cadence") == "motion" || m.at("cadence") == "cognition") << m.dump();
    }
    if (j.value("summary", false)) {
      if (j.at("pipeline") == "motion") summaryRuns = j.at("runs").get<long>();
      continue;
    }
    ASSERT_EQ(j.at("pipeline"), "motion") << "no cognition without cameras: " << j.dump();
    ++motionRuns;
    const double t = j.at("t").get<double>();
    EXPECT_GT(t, lastT) << "t is each cycle's backend time";
    lastT = t;
    double sum = 0;
    for (const auto& m : j.at("modules")) {
      EXPECT_GE(m.at("ms").get<double>(), 0);
      sum += m.at("ms").get<double>();
    }
    EXPECT_NEAR(j.at("total_ms").get<double>(), sum, 1e-9);
  }
  // One line per 12 ms cycle (1 s: 83), then the summary.
  EXPECT_EQ(motionRuns, run.at("cycles").get<int>());
  EXPECT_EQ(summaryRuns, motionRuns);
  EXPECT_GT(lastT, 0.9);
  ASSERT_FALSE(run.at("modules").empty());
  for (const auto& m : run.at("modules"))
    EXPECT_TRUE(named.count(m.get<std::string>())) << m << " is in the run's modules but in no timing line";
}

TEST(DebugChannels, WalkTraceCarriesTheWalksSteps) {
  const std::string lines = tempPath("walk.jsonl");
  const auto r = runCommand("walk --vx 200 --seconds 3 --debug walk_trace --debug-out " + lines + " --json " +
                            tempPath("walk.json"), 300);
  ASSERT_EQ(r.code, 0) << r.out;
  const auto all = jsonLines(lines);
  ASSERT_GE(all.size(), 8u) << "about two steps a second";
  int left = 0, right = 0;
  double lastT = -1, maxSpeed = 0;
  std::string lastSupport;
  for (const auto& j : all) {
    EXPECT_EQ(j.at("channel"), "walk_trace");
    const double t = j.at("t").get<double>();
    EXPECT_GT(t, lastT);
    lastT = t;
    const std::string support = j.at("support");
    EXPECT_NE(support, lastSupport) << "the support foot alternates";
    lastSupport = support;
    (support == "left" ? left : right)++;
    const double vx = j.at("speed")[0].get<double>();
    EXPECT_GE(vx, 0);
    EXPECT_LE(vx, 0.2 + 1e-9) << "the applied speed never exceeds the command";
    maxSpeed = std::max(maxSpeed, vx);
    // The swing foot lands beside the support foot: left of it when the right foot supports.
    const double y = j.at("clipped")[1].get<double>();
    EXPECT_GT(support == "right" ? y : -y, 0.05) << j.dump();
    EXPECT_LT(std::abs(j.at("clipped")[0].get<double>()), 0.12) << j.dump();
  }
  EXPECT_GT(left, 2);
  EXPECT_GT(right, 2);
  EXPECT_GT(maxSpeed, 0.1) << "the walk accelerated towards 200 mm/s";
}

TEST(DebugChannels, MatchTracesTheHomeStrikersChoices) {
  // A ball 0.6 m in front of the home robot, PLAYING: the striker goes for that ball.
  const std::string situation = tempPath("striker.json"), lines = tempPath("match.jsonl");
  std::ofstream(situation) << R"({"state": "PLAYING", "seconds": 3,
    "robots": [{"team": "home", "pose": [-2.0, 0.5, 0], "program": true}],
    "balls": [{"position": [-1.4, 0.7]}]})";
  const auto r = runCommand("match --situation " + situation + " --percepts oracle --debug behavior --debug-out " +
                                lines + " --json " + tempPath("match.json"),
                            300);
  ASSERT_EQ(r.code, 0) << r.out;
  const auto all = jsonLines(lines);
  ASSERT_GE(all.size(), 30u) << "a line per image of the home robot's 3 s";
  int chose = 0, after = 0;
  std::set<std::string> states;
  for (const auto& j : all) {
    EXPECT_EQ(j.at("channel"), "behavior");
    if (j.at("t").get<double>() < 1.0) continue;  // localized from the side line's view
    ++after;
    EXPECT_NEAR(j.at("pose")[0].get<double>(), -1.9, 0.3) << j.dump();
    EXPECT_NEAR(j.at("pose")[1].get<double>(), 0.55, 0.3) << j.dump();
    states.insert(j.at("striker").get<std::string>());
    if (j.at("striker_ball").is_array()) {
      ++chose;
      EXPECT_NEAR(j.at("striker_ball")[0].get<double>(), -1.4, 0.15) << j.dump();
      EXPECT_NEAR(j.at("striker_ball")[1].get<double>(), 0.7, 0.15) << j.dump();
    }
  }
  EXPECT_GT(chose, after * 3 / 4);
  EXPECT_TRUE(states.count("approach") && states.count("kick")) << "walks to the ball and kicks it";
}

// eval calibration --debug: each trial's robot program traces its phase 1 (how seed 41's
// wrong start side was found: docs/results/README.md).
TEST(DebugChannels, EvalCalibrationTracesTheTrialsRobotProgram) {
  const std::string lines = tempPath("eval_calibration.jsonl");
  const auto r = runCommand("eval calibration --trials 1 --lighting default --time-limit 6 --debug behavior --debug-out " +
                                lines + " --json " + tempPath("eval_calibration.json"),
                            300);
  ASSERT_EQ(r.code, 0) << r.out;
  const auto all = jsonLines(lines);
  ASSERT_GE(all.size(), 100u) << "a line per image of 6 s";
  std::set<std::string> states;
  for (const auto& j : all) {
    EXPECT_EQ(j.at("channel"), "behavior");
    states.insert(j.at("calibrate").get<std::string>());
  }
  EXPECT_TRUE(states.count("localize")) << "phase 1 starts by deciding its side line";
}

TEST(DebugChannels, UnknownChannelIsRefusedBeforeTheRun) {
  const std::string lines = tempPath("never.jsonl");
  fs::remove(lines);
  const auto r = runCommand("run --backend sim --seconds 1 --debug timing,nosuch --debug-out " + lines, 60);
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_NE(r.out.find("--debug"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("nosuch"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("walk_trace"), std::string::npos) << "lists the known channels: " << r.out;
  EXPECT_FALSE(fs::exists(lines));
  const auto out = runCommand("walk --debug-out " + lines, 60);
  EXPECT_EQ(out.code, 2) << "--debug-out without --debug: " << out.out;
}

TEST(DebugChannels, StdoutKeepsOnlyTheJson) {
  // perceive writes its JSON to stdout; the debug lines go to stderr by default.
  const std::string err = tempPath("perceive.err");
  const std::string cmd = std::string(NAO_BINARY) + " perceive " + NAO_SOURCE_DIR +
                          "/docs/images/sim_top_calibration_view.png --debug timing,line_rejects 2>" + err;
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[4096];
  while (std::size_t n = fread(buf, 1, sizeof buf, p)) out.append(buf, n);
  const int status = pclose(p);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << slurp(err);
  EXPECT_TRUE(nlohmann::json::parse(out, nullptr, false).is_object()) << out.substr(0, 300);
  bool timing = false;
  for (const auto& j : jsonLines(err, true)) {
    if (j.at("channel") == "timing") {
      timing = true;
      EXPECT_EQ(j.at("pipeline"), "vision_top");
      EXPECT_GE(j.at("modules").size(), 10u);
    } else {
      EXPECT_EQ(j.at("channel"), "line_rejects");
      EXPECT_FALSE(j.at("reason").get<std::string>().empty());
    }
  }
  EXPECT_TRUE(timing);
}

}  // namespace
