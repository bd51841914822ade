// The whole Autonomous Calibration Challenge in the simulator, as the README's main job runs
// it (`calibration-challenge --seed 1`), scored against the simulator's truth: no termination,
// every report within 0.05 m of the truth (the acceptance's bound), the phases within their
// times, the six offsets within 0.15 deg, the robot walked (no jump), the pictures written;
// then the same command again gives the same JSON (wall times aside). Bad options give one
// line and exit 2.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "support/RunCommand.h"

namespace nao {
namespace {

using test::CommandResult;
using test::runCommand;

nlohmann::json readJson(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// The JSON without what the machine's speed decides.
nlohmann::json withoutWallTimes(nlohmann::json j) {
  for (auto& [name, phase] : j["phases"].items()) phase.erase("wall_s");
  j.erase("files");
  return j;
}

TEST(CalibrationChallenge, SeedOneScoresWithinTheBoundsAndAgainTheSame) {
  if (std::getenv("NAO_TEST_QUICK")) GTEST_SKIP() << "a whole challenge: the Release stage runs it";
  const auto dir = std::filesystem::temp_directory_path() / "nao_challenge_sim_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const CommandResult r = runCommand("calibration-challenge --seed 1 --images " + (dir / "out").string() + " --json " +
                                     (dir / "a.json").string());
  ASSERT_EQ(r.code, 0) << r.out;
  const nlohmann::json a = readJson(dir / "a.json");
  EXPECT_TRUE(a["terminated"].is_null()) << a["terminated"];
  EXPECT_EQ(a["falls"].get<int>(), 0);
  ASSERT_EQ(a["tasks"].size(), 5u);
  const char* names[5] = {"ball_own", "walk_own_goal", "walk_center", "ball_opponent", "walk_opponent_goal"};
  for (int k = 0; k < 5; ++k) {
    const nlohmann::json& t = a["tasks"][k];
    EXPECT_EQ(t["task"], names[k]);
    ASSERT_FALSE(t["error_m"].is_null()) << t.dump();
    EXPECT_LE(t["error_m"].get<double>(), 0.05) << t.dump();
    EXPECT_EQ(t["error_rounded_m"].get<double>(), 0.0) << t.dump();
    EXPECT_GT(t["sim_s"].get<double>(), 1.0) << "a task takes time: " << t.dump();
  }
  // The ball reports name the taped balls, not the phase 1 ones.
  EXPECT_LT(a["tasks"][0]["truth"][0].get<double>(), 0);
  EXPECT_GT(a["tasks"][3]["truth"][0].get<double>(), 0);
  EXPECT_EQ(a["tasks"][0]["truth"], a["balls"]["phase2"][0]);
  const double calibration = a["phases"]["calibration"]["sim_s"], evaluation = a["phases"]["evaluation"]["sim_s"];
  EXPECT_LE(calibration, 120);
  EXPECT_LE(evaluation, 180);
  EXPECT_EQ(a["categories"]["calibration_time_s"].get<double>(), std::round(calibration / 5) * 5);
  for (int k = 0; k < 6; ++k) EXPECT_LE(std::abs(a["offsets"]["error_deg"][k].get<double>()), 0.15) << k;
  EXPECT_TRUE(a["offsets"]["applied"].get<bool>());
  EXPECT_GT(a["path_m"].get<double>(), 10.0) << "three spots, two balls: metres of walking";
  // The track: the truth and the robot's belief once a second and at the end; at each walk
  // report the robot stands where the referee measured it, and believes itself there.
  const nlohmann::json& track = a["track"];
  ASSERT_GE(track.size(), static_cast<std::size_t>(calibration + evaluation));
  for (std::size_t i = 1; i + 1 < track.size(); ++i)
    EXPECT_NEAR(track[i]["t"].get<double>() - track[i - 1]["t"].get<double>(), 1.0, 0.02) << i;
  int walksChecked = 0;
  for (const auto& e : a["events"]) {
    if (e["kind"] != "task" || e["text"].get<std::string>().rfind("walk_", 0) != 0) continue;
    const std::string task = e["text"].get<std::string>().substr(0, e["text"].get<std::string>().find(':'));
    const auto& report = *std::find_if(a["tasks"].begin(), a["tasks"].end(), [&](const nlohmann::json& t) { return t["task"] == task; });
    const auto at = std::min_element(track.begin(), track.end(), [&](const nlohmann::json& p, const nlohmann::json& q) {
      return std::abs(p["t"].get<double>() - e["t"].get<double>()) < std::abs(q["t"].get<double>() - e["t"].get<double>());
    });
    ASSERT_LE(std::abs((*at)["t"].get<double>() - e["t"].get<double>()), 0.5);
    for (int k = 0; k < 2; ++k) {
      EXPECT_NEAR((*at)["truth"][k].get<double>(), report["reported"][k].get<double>(), 0.03) << task;
      EXPECT_NEAR((*at)["belief"][k].get<double>(), report["truth"][k].get<double>(), 0.1) << task;
    }
    ++walksChecked;
  }
  EXPECT_EQ(walksChecked, 3);
  // The event log: the referee's buttons and taps, the robot's speech, in order of time.
  int taps = 0, speech = 0;
  double last = -1;
  for (const auto& e : a["events"]) {
    EXPECT_GE(e["t"].get<double>(), last);
    last = e["t"].get<double>();
    taps += e["kind"] == "tap";
    speech += e["kind"] == "speech";
  }
  EXPECT_EQ(taps, 4);
  EXPECT_GE(speech, 8);  // two mode acknowledgements, "Calibration finished", five reports
  // The pictures: the field from above and the views at each report.
  for (const char* file : {"field.png", "calibration_after.png", "report_1_ball_own_top.png", "report_4_ball_opponent_bottom.png"})
    EXPECT_FALSE(cv::imread((dir / "out" / file).string()).empty()) << file;
  std::filesystem::remove_all(dir);
}

// Same seed, same challenge: each phase's first 12 s twice (the calibration phase, then the
// evaluation phase alone), JSON equal but for wall times. A whole challenge takes 3 min.
TEST(CalibrationChallenge, SameSeedSameChallenge) {
  if (std::getenv("NAO_TEST_QUICK")) GTEST_SKIP() << "four runs of 12 s: the Release stage runs it";
  const auto dir = std::filesystem::temp_directory_path() / "nao_challenge_same_seed";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  for (const std::string phase : {"", " --skip-calibration"}) {
    const std::string args = "calibration-challenge --seed 4 --time-limit 12 --randomize" + phase + " --json ";
    const CommandResult a = runCommand(args + (dir / "a.json").string());
    const CommandResult b = runCommand(args + (dir / "b.json").string());
    ASSERT_TRUE(std::filesystem::exists(dir / "a.json")) << a.out;
    EXPECT_EQ(a.code, b.code);
    const nlohmann::json ja = readJson(dir / "a.json"), jb = readJson(dir / "b.json");
    EXPECT_GE(ja["events"].size(), 2u) << "the referee's buttons and the robot's answer" << phase;
    EXPECT_EQ(withoutWallTimes(ja), withoutWallTimes(jb)) << phase;
    std::filesystem::remove(dir / "a.json");
    std::filesystem::remove(dir / "b.json");
  }
  std::filesystem::remove_all(dir);
}

// eval challenge writes a row per trial as it ends; a row cut short (a trial interrupted while
// its row was written) runs again, and the aggregate comes out the same as uninterrupted. Rows
// of other settings are refused. (Short phases: each trial ends at the 2 s phase limit.)
TEST(EvalChallenge, ResumesFromATruncatedRowsFileToTheSameAggregate) {
  const auto dir = std::filesystem::temp_directory_path() / "nao_eval_challenge_rows";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string rows = (dir / "rows.jsonl").string();
  const std::string common = "eval challenge --trials 2 --time-limit 2 --lighting default --rows " + rows;
  ASSERT_EQ(runCommand(common + " --json " + (dir / "a.json").string()).code, 0);
  std::string text;
  {
    std::ifstream in(rows);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  ASSERT_EQ(std::count(text.begin(), text.end(), '\n'), 2);
  const nlohmann::json a = readJson(dir / "a.json");
  EXPECT_EQ(a["trials"], 2);
  EXPECT_EQ(a["terminations"]["phase_time"], 2);
  ASSERT_EQ(a["failures"].size(), 2u);
  EXPECT_EQ(a["failures"][0]["seed"], 1);
  // The second row cut in the middle: its trial runs again, the first does not.
  const std::size_t cut = text.find('\n') + 1 + 40;
  std::ofstream(rows, std::ios::trunc) << text.substr(0, cut);
  const CommandResult again = runCommand(common + " --json " + (dir / "b.json").string());
  ASSERT_EQ(again.code, 0) << again.out;
  EXPECT_NE(again.out.find("line 2 is truncated"), std::string::npos) << again.out;
  EXPECT_EQ(readJson(dir / "b.json"), a);
  std::string resumed;
  {
    std::ifstream in(rows);
    resumed.assign(std::istreambuf_iterator<char>(in), {});
  }
  EXPECT_EQ(std::count(resumed.begin(), resumed.end(), '\n'), 2);
  EXPECT_EQ(resumed.substr(0, text.find('\n')), text.substr(0, text.find('\n'))) << "the first trial did not run again";
  // Other settings: refused, nothing run.
  const CommandResult other = runCommand("eval challenge --trials 2 --time-limit 3 --lighting default --rows " + rows);
  EXPECT_EQ(other.code, 2) << other.out;
  EXPECT_EQ(std::count(other.out.begin(), other.out.end(), '\n'), 1) << other.out;
  EXPECT_NE(other.out.find("rows of other settings"), std::string::npos) << other.out;
  std::filesystem::remove_all(dir);
}

TEST(CalibrationChallenge, BadOptionsGiveOneLineAndNothingWritten) {
  const auto dir = std::filesystem::temp_directory_path() / "nao_challenge_bad_options";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string json = " --json " + (dir / "x.json").string() + " --images " + (dir / "img").string();
  for (const std::string args : {"calibration-challenge --start middle", "calibration-challenge --miscalibration 1,2,x,4,5,6",
                                 "calibration-challenge --miscalibration 1,2,3", "calibration-challenge --lighting nowhere",
                                 "calibration-challenge --venue nowhere", "eval challenge --venue nowhere --trials 1"}) {
    const CommandResult r = runCommand(args + json);
    EXPECT_EQ(r.code, 2) << args << ": " << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << args << ": " << r.out;
    EXPECT_TRUE(std::filesystem::is_empty(dir)) << args << " left a file";
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace nao
