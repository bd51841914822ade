// The calibration challenge's phase 1 in the simulator, done by the robot program, against the
// injected truth: a small `eval calibration` with the acceptance thresholds of the full one (per
// parameter median |error| <= 0.1 deg, 95th percentile <= 0.25 deg, every trial reported and
// converged, Gauss-Newton and Ceres within 0.02 deg, each solve <= 0.2 s, field lines reprojected
// within 1 px RMS, the phase within 120 s), that the robot walked there (a continuous path, no
// jump), and no offsets -> zero. Then the `calibrate` command end to end: the estimate against
// the injected offsets, the paper's Fig. 2 pictures (projected field lines over paint after, not
// before), the stored result, and bad options (challenge_sim_test checks the same result for
// the same seed on the whole challenge).
#include <gtest/gtest.h>


#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "perception/calibration/CalibrationStore.h"
#include "robot/Paths.h"
#include "scenarios/Calibrate.h"
#include "support/JsonTimes.h"
#include "support/RunCommand.h"

namespace nao::sim {
namespace {

constexpr double kDeg = M_PI / 180;

// What every run must show: reported with the arm up, walked (no jump: at most 2 cm per 12 ms
// cycle, more than 1 m from the start), did not fall, within the time.
void expectWalkedAndReported(const CalibrationRunResult& r) {
  EXPECT_TRUE(r.finished) << "no 'Calibration finished' with an arm up";
  EXPECT_TRUE(r.applied) << r.solution.reason;
  EXPECT_FALSE(r.fell);
  EXPECT_LT(r.maxStep, 0.02) << "the robot jumped: it must walk";
  EXPECT_GT(r.pathLength, 1.0) << "from the start to the goal box is more than 1 m";
  EXPECT_LE(r.phaseSeconds, 120);
}

TEST(CalibrationSim, RandomOffsetsLightingAndSides) {
  CalibrationEvalOptions o;
  o.trials = std::getenv("NAO_TEST_QUICK") ? 1 : 2;
  o.seed = 11;
  o.field = FieldDimensions::load(dataPath("config/field_dimensions.json"));
  o.lightings = Lighting::sweep(dataPath("config/lighting.json"));
  const CalibrationEvalResult r = evalCalibration(o);
  EXPECT_EQ(r.trials, o.trials);
  EXPECT_EQ(r.finished, o.trials);
  EXPECT_EQ(r.converged, o.trials);
  EXPECT_EQ(r.accepted, o.trials);
  for (int k = 0; k < 6; ++k) {
    EXPECT_LE(r.medianAbsErrorDeg[k], 0.1) << CameraCalibration::kNames[k];
    EXPECT_LE(r.p95AbsErrorDeg[k], 0.25) << CameraCalibration::kNames[k];
  }
  EXPECT_LE(r.solverAgreementMaxDeg, 0.02);
  EXPECT_LE(r.solveSecondsMax, 0.2);
  EXPECT_LE(r.otherSolveSecondsMax, 0.2);
  EXPECT_LE(r.reprojectionMaxPx, 1.0);
  for (const auto& t : r.trialResults) {
    expectWalkedAndReported(t.run);
    EXPECT_GE(t.run.samples, 6) << "lighting " << t.lighting;
    EXPECT_LT(t.run.reprojectionPx, t.run.reprojectionBeforePx);
  }
}

// The robot may start on either side line; from the left it calibrates at the left side of
// its goal box. With no offsets injected, Ceres finds none: the solve adds no bias of its own.
// (Random offsets from either side: RandomOffsetsLightingAndSides and the challenge test.)
TEST(CalibrationSim, LeftStartWithoutOffsetsStaysNearZero) {
  if (std::getenv("NAO_TEST_QUICK")) GTEST_SKIP() << "a whole phase: the Release stage runs it";
  CalibrationRunOptions o;
  o.field = FieldDimensions::load(dataPath("config/field_dimensions.json"));
  o.side = 1;
  modules::Calibrator::Params calibrator;
  calibrator.solver = "ceres";
  o.calibrator = calibrator;
  const CalibrationRunResult r = runCalibration(o);
  expectWalkedAndReported(r);
  ASSERT_TRUE(r.solution.solver.converged) << r.solution.solver.message;
  ASSERT_TRUE(r.solution.accepted) << r.solution.reason;
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(r.estimate.toArray()[k] / kDeg, 0.0, 0.1) << CameraCalibration::kNames[k];
  EXPECT_LE(r.reprojectionPx, 1.0);
  for (const ViewRecord& v : r.views) EXPECT_GT(v.truePose.y(), 0) << "views from the left side of the box";
}

// ---- The command ----

using test::CommandResult;
using test::runCommand;

nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// Of the red pixels drawn into `figure` over the camera image `raw` (placed at `origin` in the
// figure), the fraction that lie on painted line (a bright, unsaturated pixel of the raw image
// within 1 px). Projected field lines drawn with good offsets lie on the paint; with wrong ones
// mostly beside it. Lines hidden behind goal posts and thin far lines keep it below 1.
double redOnPaint(const cv::Mat& figure, const cv::Mat& raw, cv::Point origin, int* redPixels) {
  int red = 0, onPaint = 0;
  for (int y = 0; y < raw.rows; ++y)
    for (int x = 0; x < raw.cols; ++x) {
      const cv::Vec3b f = figure.at<cv::Vec3b>(y + origin.y, x + origin.x);  // BGR
      if (!(f[2] > 150 && f[1] < 90 && f[0] < 90)) continue;
      ++red;
      bool paint = false;
      for (int dy = -1; dy <= 1 && !paint; ++dy)
        for (int dx = -1; dx <= 1 && !paint; ++dx) {
          const int yy = y + dy, xx = x + dx;
          if (yy < 0 || xx < 0 || yy >= raw.rows || xx >= raw.cols) continue;
          const cv::Vec3b q = raw.at<cv::Vec3b>(yy, xx);
          // White in all three channels; 110, not higher: the camera's vignetting takes a line in a
          // corner of the top image to 0.6 of its brightness in the centre.
          paint = q[0] > 110 && q[1] > 110 && q[2] > 110;
        }
      onPaint += paint;
    }
  *redPixels = red;
  return red ? static_cast<double>(onPaint) / red : 0;
}

TEST(CalibrateCommand, EstimatesPicturesStoreAndSameSeedSameResult) {
  // Under the sanitizers a whole phase takes a quarter of an hour: RandomOffsetsLightingAndSides
  // runs the robot program's calibration there.
  if (std::getenv("NAO_TEST_QUICK")) GTEST_SKIP() << "a whole phase: the Release stage runs it";
  const auto dir = std::filesystem::temp_directory_path() / "nao_calibrate_command_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string images = (dir / "images").string(), store = (dir / "store").string();
  const std::string common = "calibrate --seed 3 --miscalibration 2.5,-2,-2.5,2.8,2,-2.5";
  const std::string log = (dir / "views.calog").string();
  const CommandResult r = runCommand(common + " --compare --images " + images + " --save --store " + store +
                                     " --record " + log + " --json " + (dir / "a.json").string());
  ASSERT_EQ(r.code, 0) << r.out;
  const nlohmann::json a = readJson((dir / "a.json").string());
  EXPECT_TRUE(a["converged"].get<bool>());
  EXPECT_TRUE(a["accepted"].get<bool>());
  EXPECT_TRUE(a["saved"].get<bool>());
  EXPECT_TRUE(a["finished"].get<bool>());
  EXPECT_TRUE(a["applied"].get<bool>());
  EXPECT_LE(a["phase_s"].get<double>(), 120);
  EXPECT_LE(a["reprojection_px"].get<double>(), 1.0);
  EXPECT_GT(a["reprojection_before_px"].get<double>(), 5.0);  // the injected offsets are visible
  for (const char* name : CameraCalibration::kNames) {
    EXPECT_NEAR(a["estimated_deg"][name].get<double>(), a["true_deg"][name].get<double>(), 0.1) << name;
    EXPECT_LE(std::abs(a["other_solver"]["difference_deg"][name].get<double>()), 0.02) << name;
  }

  // The stored result is the estimate, under the simulated robot's head id.
  const calibration::CalibrationStore st(store);
  const auto rec = st.load(a["head_id"].get<std::string>());
  ASSERT_TRUE(rec.has_value());
  for (int k = 0; k < 6; ++k)
    EXPECT_NEAR(rec->offsets.toArray()[k] / kDeg, a["estimated_deg"][CameraCalibration::kNames[k]].get<double>(), 1e-9);

  // Fig. 2: the straight-ahead top and bottom views, projected field lines red.
  const cv::Mat before = cv::imread(images + "/calibration_before.png"), after = cv::imread(images + "/calibration_after.png");
  const cv::Mat top = cv::imread(images + "/view_02_top_yaw+000_raw.png"), bottom = cv::imread(images + "/view_07_bottom_yaw+000_raw.png");
  ASSERT_FALSE(before.empty() || after.empty() || top.empty() || bottom.empty()) << r.out;
  ASSERT_EQ(after.rows, top.rows + bottom.rows);
  ASSERT_EQ(after.cols, std::max(top.cols, bottom.cols));
  const cv::Point topAt((after.cols - top.cols) / 2, 0), bottomAt((after.cols - bottom.cols) / 2, top.rows);
  int red = 0;
  const double topAfter = redOnPaint(after, top, topAt, &red);
  EXPECT_GT(red, 500);
  const double topBefore = redOnPaint(before, top, topAt, &red);
  EXPECT_GT(red, 500);
  const double bottomAfter = redOnPaint(after, bottom, bottomAt, &red);
  EXPECT_GT(red, 300);
  const double bottomBefore = redOnPaint(before, bottom, bottomAt, &red);
  EXPECT_GT(red, 300);
  std::printf("red on paint: top %.2f -> %.2f, bottom %.2f -> %.2f\n", topBefore, topAfter, bottomBefore, bottomAfter);
  EXPECT_GE(topAfter, 0.7);
  EXPECT_GE(bottomAfter, 0.5);
  EXPECT_LE(topBefore, topAfter - 0.3);
  EXPECT_LE(bottomBefore, bottomAfter - 0.3);

  // The recorded views through the robot program's Calibrator again, without a simulator: the
  // same verdicts and the live solution.
  const std::string head = a["head_id"].get<std::string>();
  const CommandResult b = runCommand("calibrate --from-log " + log + " --head-id " + head + " --json " + (dir / "b.json").string());
  ASSERT_EQ(b.code, 0) << b.out;
  const nlohmann::json fromLog = readJson((dir / "b.json").string());
  EXPECT_EQ(fromLog["head_id"], head);
  EXPECT_EQ(fromLog["records"].get<int>(), static_cast<int>(a["views"].size()));
  EXPECT_EQ(fromLog["verdicts_as_live"], fromLog["records"]);
  // Both ran the robot program's line source (once `calibrate` ran LSD alone by default, and
  // its from-log replay of a challenge's log judged 6 of 16 views otherwise than the robot).
  const std::string configLines =
      readJson(dataPath("config/parameters/Calibrator.json")).at("lines").get<std::string>();
  EXPECT_EQ(a["lines"], configLines);
  EXPECT_EQ(fromLog["lines"], configLines);
  // Each accepted view names its segments' source; each view the solve used has its residuals
  // (the right angles within a degree, the depth within the acceptance's 3 cm).
  int withResiduals = 0;
  for (const auto& v : fromLog["views"]) {
    if (!v["accepted"].get<bool>()) continue;
    EXPECT_FALSE(v["source"].get<std::string>().empty()) << v.dump();
    if (!v.contains("residuals")) continue;
    ++withResiduals;
    EXPECT_LT(std::abs(v["residuals"]["angle1_deg"].get<double>()), 1.0) << v.dump();
    EXPECT_LT(std::abs(v["residuals"]["angle2_deg"].get<double>()), 1.0) << v.dump();
    EXPECT_LT(std::abs(v["residuals"]["depth_m"].get<double>()), 0.03) << v.dump();
  }
  EXPECT_EQ(withResiduals, fromLog["samples_used"].get<int>());
  EXPECT_TRUE(fromLog["accepted"].get<bool>());
  for (const char* name : CameraCalibration::kNames)
    EXPECT_NEAR(fromLog["estimated_deg"][name].get<double>(), a["estimated_deg"][name].get<double>(), 1e-9) << name;

  // A log cut short, and another robot's log: one line naming the file, exit 2, nothing written.
  std::string bytes;
  {
    std::ifstream in(log, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string cut = (dir / "cut.calog").string();
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() * 2 / 3);
  const std::string out = (dir / "c.json").string();
  for (const std::string& args : {"calibrate --from-log " + cut + " --json " + out,
                                  "calibrate --from-log " + log + " --head-id another-head --save --store " + store + " --json " + out}) {
    const CommandResult bad = runCommand(args);
    EXPECT_EQ(bad.code, 2) << args << ": " << bad.out;
    EXPECT_EQ(std::count(bad.out.begin(), bad.out.end(), '\n'), 1) << bad.out;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
    if (args.find("cut") != std::string::npos) {
      EXPECT_NE(bad.out.find(cut + ": record "), std::string::npos) << bad.out;
      EXPECT_NE(bad.out.find("truncated"), std::string::npos) << bad.out;
    } else {
      EXPECT_NE(bad.out.find("recorded by head '" + head + "', not by 'another-head'"), std::string::npos) << bad.out;
    }
  }
  EXPECT_FALSE(st.load("another-head").has_value());

  // (Same seed, same result: challenge_sim_test runs the whole challenge twice.)
  std::filesystem::remove_all(dir);
}

TEST(CalibrateCommand, BadOptionsGiveOneLine) {
  for (const char* args : {"calibrate --solver newton", "calibrate --placement-error 0,0,0", "calibrate --lines hough",
                           "calibrate --miscalibration 1,2,3", "calibrate --from-log /nonexistent/views.calog",
                           "calibrate --from-log /dev/null --lighting dark", "calibrate --head-id sim-r0-head",
                           "calibrate --from-log /dev/null", "calibration-challenge --skip-calibration --record /tmp/x.calog"}) {
    const CommandResult r = runCommand(args);
    EXPECT_EQ(r.code, 2) << args << ": " << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << args << ": " << r.out;
  }
}

std::string fileText(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// eval calibration writes a row per trial as it ends. A row cut short runs again and the
// aggregate comes out as uninterrupted; a trial is its seed's alone (seed 2 run by itself gives
// the second row); rows of other settings are refused. (2 s phases: no sample, the offsets'
// errors are the injected ones.)
TEST(EvalCalibration, RowsResumeAndEachTrialIsItsSeeds) {
  const auto dir = std::filesystem::temp_directory_path() / "nao_eval_calibration_rows";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string rows = (dir / "rows.jsonl").string();
  const std::string common = "eval calibration --trials 2 --time-limit 2 --lighting default --rows " + rows;
  ASSERT_EQ(runCommand(common + " --json " + (dir / "a.json").string()).code, 0);
  const std::string text = fileText(rows);
  ASSERT_EQ(std::count(text.begin(), text.end(), '\n'), 2);
  const nlohmann::json a = readJson((dir / "a.json").string());
  EXPECT_EQ(a["trials"], 2);
  ASSERT_EQ(a["per_trial"].size(), 2u);
  EXPECT_EQ(a["per_trial"][1]["seed"], 2);
  // Nothing calibrated in 2 s: each error is the injected offset (up to 3 deg), the largest of
  // the two trials is the aggregate's maximum.
  for (int k = 0; k < 6; ++k) {
    const char* name = CameraCalibration::kNames[k];
    double largest = 0;
    for (const auto& t : a["per_trial"]) {
      EXPECT_NEAR(t["error_deg"][name].get<double>(), -t["true_deg"][name].get<double>(), 1e-9) << name;
      largest = std::max(largest, std::abs(t["true_deg"][name].get<double>()));
    }
    EXPECT_LE(largest, 3.0);
    EXPECT_DOUBLE_EQ(a["max_abs_error_deg"][name].get<double>(), largest) << name;
  }
  // The second row cut in the middle: its trial runs again, the first does not.
  std::ofstream(rows, std::ios::trunc) << text.substr(0, text.find('\n') + 1 + 40);
  const CommandResult again = runCommand(common + " --json " + (dir / "b.json").string());
  ASSERT_EQ(again.code, 0) << again.out;
  EXPECT_NE(again.out.find("line 2 is truncated"), std::string::npos) << again.out;
  EXPECT_EQ(test::withoutTimes(readJson((dir / "b.json").string())), test::withoutTimes(a));
  const std::string resumed = fileText(rows);
  EXPECT_EQ(resumed.substr(0, text.find('\n')), text.substr(0, text.find('\n'))) << "the first trial ran again";
  // Seed 2 alone is the second trial; writing its pictures (--images: into DIR/seed_2/) changes
  // nothing else.
  const auto images = dir / "images";
  ASSERT_EQ(runCommand("eval calibration --seed 2 --trials 1 --time-limit 2 --lighting default --json " +
                       (dir / "c.json").string() + " --images " + images.string()).code, 0);
  nlohmann::json c = readJson((dir / "c.json").string())["per_trial"][0];
  EXPECT_TRUE(std::filesystem::is_directory(images / "seed_2"));
  for (const auto& f : c["files"]) EXPECT_TRUE(std::filesystem::exists(f.get<std::string>())) << f;
  c.erase("files");
  nlohmann::json second = a["per_trial"][1];
  second.erase("files");
  EXPECT_EQ(test::withoutTimes(c), test::withoutTimes(second));
  // Other settings: refused, nothing run.
  const CommandResult other = runCommand("eval calibration --trials 2 --time-limit 3 --lighting default --rows " + rows);
  EXPECT_EQ(other.code, 2) << other.out;
  EXPECT_NE(other.out.find("rows of other settings"), std::string::npos) << other.out;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace nao::sim
