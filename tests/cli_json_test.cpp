// Every command's `--json -`: stdout carries one JSON document and nothing else (progress and
// warnings go to stderr), the exit code is the command's, and two runs with the same --seed
// print the same JSON where the command promises it.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "apps/cli/CommandLine.h"
#include "tests/support/RunCommand.h"

namespace {

namespace fs = std::filesystem;

using Output = nao::test::SplitResult;

Output runJson(const std::string& args) { return nao::test::runCommandSplit(args + " --json -", 600); }

// The smallest run of every command (each declared in apps/cli/Declarations.cpp).
std::string smallRun(const std::string& path, const std::string& dir) {
  const std::string image = std::string(NAO_SOURCE_DIR) + "/docs/images/sim_top_calibration_view.png";
  if (path == "render") return "render --out " + dir + "/r.png";
  if (path == "run") return "run --seconds 0.5";
  if (path == "bench sim") return "bench sim --seconds 1 --repeats 1";
  if (path == "bench program") return "bench program --seconds 1 --repeats 1";
  if (path == "bench match") return "bench match --seconds 2 --repeats 1 --percepts oracle";
  if (path == "bench perception") return "bench perception --frames 2 --repeats 1";
  if (path == "bench calibration") return "bench calibration --repeats 1 --time-limit 3";
  if (path == "perceive") return "perceive " + image;
  if (path == "eval perception") return "eval perception --trials 1 --lighting default";
  if (path == "eval real") return "eval real --dir " + std::string(NAO_SHARED_DIR) + "/data/real-goalbox-images";
  if (path == "eval calibration") return "eval calibration --trials 1 --lighting default --time-limit 3";
  if (path == "eval localization") return "eval localization --trials 1 --seconds 5 --lighting default --roll-every 0";
  if (path == "eval walk") return "eval walk --trials 1 --seconds 2";
  if (path == "eval walk-to") return "eval walk-to --trials 1";
  if (path == "eval getup") return "eval getup --trials 1 --seconds 1";
  if (path == "walk") return "walk --vx 200 --seconds 1";
  if (path == "kick") return "kick --trials 1";
  if (path == "train ball") return "train ball --scenes 5 --lightings 1 --iterations 2 --out " + dir + "/ball.yml";
  if (path == "train friction") return "train friction --rolls 2 --max-speed 1";
  if (path == "calibrate") return "calibrate --time-limit 3";
  if (path == "eval challenge") return "eval challenge --trials 1 --lighting default --time-limit 2";
  if (path == "calibration-challenge") return "calibration-challenge --time-limit 3";
  if (path == "match") return "match --seconds 3";
  if (path == "eval match") return "eval match --games 1 --seconds 3 --lighting default";
  if (path == "modules") return "modules";
  if (path == "batch")
    return "batch eval localization --trials 1 --seconds 5 --lighting default --roll-every 0 --percepts oracle --dir " + dir + "/batch";
  return "";
}

TEST(CliJson, EveryCommandPrintsOnlyJsonOnStdout) {
  const fs::path dir = fs::path(::testing::TempDir()) / "cli_json";
  fs::remove_all(dir);
  fs::create_directories(dir);
  nao::cli::CommandLine cl;
  int checked = 0;
  for (const nao::cli::Command* c : cl.commands()) {
    const std::string args = smallRun(c->path(), dir.string());
    ASSERT_FALSE(args.empty()) << "no small run for '" << c->path() << "': add one here";
    const Output o = runJson(args);
    // 0 or 1 (a run that worked but missed a figure, e.g. a getup cut short at 1 s): both write JSON.
    EXPECT_TRUE(o.code == 0 || o.code == 1) << args << ": exit " << o.code << "\n" << o.err;
    const auto j = nlohmann::json::parse(o.out, nullptr, false);
    EXPECT_TRUE(j.is_object()) << args << ": stdout is not one JSON object:\n" << o.out.substr(0, 400);
    EXPECT_FALSE(fs::exists(fs::current_path() / "MUJOCO_LOG.TXT"));
    ++checked;
  }
  EXPECT_EQ(checked, 26);
}

// bench match: both percept modes in one run, each game's wall time split into parts that add
// up, and the renderer named where one rendered. (How fast is the benchmark's to say, not a
// test's: docs/scaling.md.)
TEST(CliJson, BenchMatchTimesBothPerceptModesSideBySide) {
  const Output o = runJson("bench match --seconds 3 --repeats 1");
  ASSERT_EQ(o.code, 0) << o.err;
  const auto j = nlohmann::json::parse(o.out);
  EXPECT_GT(j["rtf"].get<double>(), 0);
  EXPECT_GT(j["rtf_oracle"].get<double>(), 0);
  const double ratio = j["rtf_oracle"].get<double>() / j["rtf"].get<double>();  // of rounded figures
  EXPECT_NEAR(j["oracle_speedup"].get<double>(), ratio, 0.01 * ratio);
  EXPECT_FALSE(j["gl_vendor"].get<std::string>().empty());
  EXPECT_FALSE(j["gl_renderer"].get<std::string>().empty());
  ASSERT_EQ(j["runs"].size(), 2u);
  for (const auto& run : j["runs"]) {
    EXPECT_NEAR(run["simulated_s"].get<double>(), 3.0, 0.02) << run.dump();
    double sum = 0;
    for (const auto& [part, share] : run["wall_share"].items()) {
      EXPECT_GE(share.get<double>(), part == "referee_and_rest" ? -0.02 : 0.0) << part << " " << run.dump();
      sum += share.get<double>();
    }
    EXPECT_NEAR(sum, 1.0, 1e-3) << run.dump();
  }
  // Each mode's own parts: a vision game renders, an oracle game makes views.
  EXPECT_GT(j["wall_share"]["vision"]["render"].get<double>(), 0) << o.out;
  EXPECT_FALSE(j["wall_share"]["vision"].contains("oracle_views")) << o.out;
  EXPECT_GT(j["wall_share"]["oracle"]["oracle_views"].get<double>(), 0) << o.out;
  EXPECT_FALSE(j["wall_share"]["oracle"].contains("render")) << o.out;
}

// bench sim --profile: each camera image's stages add up to its render time, and the camera
// runs' wall shares to one.
TEST(CliJson, BenchSimProfileSplitsTheRenderIntoItsStages) {
  const Output o = runJson("bench sim --seconds 1 --repeats 1 --profile");
  ASSERT_EQ(o.code, 0) << o.err;
  const auto j = nlohmann::json::parse(o.out);
  const auto& stages = j["profile"]["render_stage_ms_median"];
  for (const char* camera : {"top", "bottom"}) {
    double sum = 0;
    for (const char* stage : {"scene", "draw", "read", "sensor"}) {
      ASSERT_TRUE(stages[camera].contains(stage)) << camera << " " << stage;
      EXPECT_GT(stages[camera][stage].get<double>(), 0) << camera << " " << stage;
      sum += stages[camera][stage].get<double>();
    }
    const double total = j[std::string("render_ms_") + camera].get<double>();
    // Medians of the parts against the median of the wholes: alike, not equal.
    EXPECT_GT(sum, 0.5 * total) << camera << ": " << stages[camera].dump();
    EXPECT_LT(sum, 1.5 * total) << camera << ": " << stages[camera].dump();
  }
  double shares = 0;
  for (const auto& [part, share] : j["profile"]["camera_run_wall_share"].items()) shares += share.get<double>();
  EXPECT_NEAR(shares, 1.0, 1e-6);
  EXPECT_GT(j["profile"]["camera_run_wall_share"]["render"].get<double>(), 0);
}

}  // namespace
