// eval localization (scenarios/LocalizationEval.h): the unchanged robot program in the
// simulator with both cameras, its RobotPose and BallModel judged by the simulator's truth.
// A short scripted walk ending in a kidnap: the pose error is small and the kidnap is
// recovered; the command's --rows: a run cut short in the middle of a row resumes to the same
// aggregate as an uninterrupted run, and the same --seed gives the same JSON. The fast percept
// mode (--percepts oracle) runs the same trial without rendering.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "perception/FieldDimensions.h"
#include "robot/Paths.h"
#include "scenarios/LocalizationEval.h"
#include "support/RunCommand.h"

namespace nao {
namespace {

namespace fs = std::filesystem;

TEST(LocalizationEval, WalkThenKidnapIsScoredAgainstTheTruth) {
  sim::LocalizationEvalOptions o;
  o.field = FieldDimensions::load(dataPath("config/field_dimensions.json"));
  o.walkSeconds = 8;
  o.kidnapEvery = 4;  // seed 3: 3 mod 4 = 3, a kidnap trial
  const nlohmann::json row = sim::runLocalizationTrial(o, 3);
  ASSERT_EQ(row.at("kind"), "kidnap");
  const nlohmann::json j = sim::aggregateLocalizationRows({row});
  std::printf("%s\n", j.dump().c_str());
  EXPECT_GT(row.at("valid").get<long>(), 200);  // both cameras at 30 Hz over ~7 s, most of it valid
  EXPECT_LT(j["position_error_m"]["median"].get<double>(), 0.05);  // 5 mm measured
  EXPECT_LT(j["position_error_m"]["p95"].get<double>(), 0.15);
  EXPECT_LT(j["heading_error_deg"]["median"].get<double>(), 1.5);
  EXPECT_EQ(j["mirrored_fraction"].get<double>(), 0.0);
  const auto& k = row.at("kidnap");
  EXPECT_GE(k.at("distance_m").get<double>(), 1.0);
  EXPECT_GE(k.at("turn_deg").get<double>(), 45.0);
  EXPECT_TRUE(k.at("recovered").get<bool>()) << k.dump();
  EXPECT_LT(k.at("error_end_m").get<double>(), 0.2);
  // The aggregate counts it.
  EXPECT_EQ(j["kidnap"]["trials"], 1);
  EXPECT_EQ(j["kidnap"]["recovered"], 1);
}

// The same trial in the fast percept mode: the same robot program, its camera percepts from
// OracleVision (the simulator's view with the vision's fitted errors) instead of rendered images.
TEST(LocalizationEval, TheFastPerceptModeLocalizesThroughTheSameRobotProgram) {
  sim::LocalizationEvalOptions o;
  o.field = FieldDimensions::load(dataPath("config/field_dimensions.json"));
  o.walkSeconds = 8;
  o.kidnapEvery = 4;
  o.oracle = true;
  const nlohmann::json row = sim::runLocalizationTrial(o, 3);
  ASSERT_EQ(row.at("kind"), "kidnap");
  EXPECT_EQ(row.at("settings").at("percepts"), "oracle");
  const nlohmann::json j = sim::aggregateLocalizationRows({row});
  std::printf("%s\n", j.dump().c_str());
  EXPECT_GT(row.at("valid").get<long>(), 200);
  EXPECT_LT(j["position_error_m"]["median"].get<double>(), 0.05);
  EXPECT_LT(j["position_error_m"]["p95"].get<double>(), 0.15);
  EXPECT_LT(j["heading_error_deg"]["median"].get<double>(), 1.5);
  EXPECT_EQ(j["mirrored_fraction"].get<double>(), 0.0);
  EXPECT_TRUE(row.at("kidnap").at("recovered").get<bool>()) << row.at("kidnap").dump();
}

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

TEST(LocalizationEval, RowsResumeToTheSameAggregate) {
  const fs::path dir = fs::path(::testing::TempDir()) / "localization_eval_rows";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string rows = (dir / "rows.jsonl").string();
  const std::string args = "eval localization --trials 2 --seed 5 --seconds 5 --kidnap-every 0 --roll-every 0 --json ";
  const auto whole = test::runCommand(args + (dir / "a.json").string() + " --rows " + rows, 300);
  ASSERT_EQ(whole.code, 0) << whole.out;
  EXPECT_NE(whole.out.find("trial 2/2"), std::string::npos) << whole.out;  // progress on stderr
  const std::string a = slurp(dir / "a.json");
  const std::string fullRows = slurp(rows);
  ASSERT_EQ(std::count(fullRows.begin(), fullRows.end(), '\n'), 2);

  // Interrupted while the second row was written: half of it on disk.
  const std::size_t second = fullRows.find('\n') + 1;
  std::ofstream(rows, std::ios::binary | std::ios::trunc) << fullRows.substr(0, second + (fullRows.size() - second) / 2);
  const auto resumed = test::runCommand(args + (dir / "b.json").string() + " --rows " + rows, 300);
  ASSERT_EQ(resumed.code, 0) << resumed.out;
  EXPECT_NE(resumed.out.find("truncated"), std::string::npos) << resumed.out;
  EXPECT_EQ(slurp(dir / "b.json"), a);  // the rerun trial gives the same row: same seed, same figures
  const std::string newRows = slurp(rows);
  EXPECT_EQ(std::count(newRows.begin(), newRows.end(), '\n'), 2);

  // Everything in the file: nothing runs, the same aggregate.
  const auto again = test::runCommand(args + (dir / "c.json").string() + " --rows " + rows, 60);
  ASSERT_EQ(again.code, 0) << again.out;
  EXPECT_EQ(slurp(dir / "c.json"), a);

  const auto j = nlohmann::json::parse(a);
  EXPECT_EQ(j["trials"], 2);
  for (const char* key : {"position_error_m", "heading_error_deg", "mirrored_fraction", "kidnap", "ball", "by_lighting"})
    EXPECT_TRUE(j.contains(key)) << key;
  for (const char* bin : {"0-2", "2-4", "4-6"}) EXPECT_TRUE(j["ball"]["static_error_m"].contains(bin)) << bin;
  EXPECT_LT(j["position_error_m"]["median"].get<double>(), 0.10);

  // Rows of other settings are refused (exit 2), the file kept.
  const auto other = test::runCommand("eval localization --trials 2 --seed 5 --seconds 6 --rows " + rows, 60);
  EXPECT_EQ(other.code, 2) << other.out;
  EXPECT_EQ(slurp(rows), newRows);
  const auto oracle = test::runCommand(args + (dir / "d.json").string() + " --percepts oracle --rows " + rows, 60);
  EXPECT_EQ(oracle.code, 2) << oracle.out;
  EXPECT_NE(oracle.out.find("percepts"), std::string::npos) << oracle.out;
  EXPECT_EQ(slurp(rows), newRows);
}

}  // namespace
}  // namespace nao
