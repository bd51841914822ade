// The nao-soccer command: bad input exits 2 with one line naming the file/flag and the problem.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "robot/Paths.h"
#include "support/RunCommand.h"

namespace {

using Result = nao::test::CommandResult;

Result run(const std::string& args) { return nao::test::runCommand(args); }

std::string tempFile(const std::string& name, const std::string& content) {
  const std::string path = std::string(::testing::TempDir()) + name;
  std::ofstream(path) << content;
  return path;
}

std::string slurpFile(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

int lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

void expectOneLineError(const Result& r, const std::string& mustContain1, const std::string& mustContain2 = "") {
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_EQ(lines(r.out), 1) << r.out;
  EXPECT_NE(r.out.find(mustContain1), std::string::npos) << r.out;
  if (!mustContain2.empty()) {
    EXPECT_NE(r.out.find(mustContain2), std::string::npos) << r.out;
  }
}

const std::string kOut = " --out " + std::string(::testing::TempDir()) + "cli.png";

TEST(Cli, UnknownFlag) { expectOneLineError(run("render --camera top --frobnicate 3" + kOut), "--frobnicate", "not an option"); }

// An option another command takes is refused, not ignored (eval walk-to has no field).
TEST(Cli, OptionOfAnotherCommand) {
  expectOneLineError(run("eval walk-to --field config/field_dimensions.json"), "--field", "not an option of 'eval walk-to'");
  expectOneLineError(run("eval perception --randomize"), "--randomize");
  expectOneLineError(run("run --backend sim --team 5"), "--team", "--backend nao");
}

// The LoLA clock only with cameras whose frames carry it; a socket path must fit a socket.
TEST(Cli, NaoClockAndCameraSockets) {
  expectOneLineError(run("run --backend nao --clock lola --cameras v4l2"), "--clock lola", "socket:PATH");
  expectOneLineError(run("run --backend sim --clock lola"), "--clock");
  expectOneLineError(run("run --backend nao --clock sundial"), "--clock", "monotonic|lola");
  expectOneLineError(run("run --backend nao --cameras socket:"), "--cameras", "socket: needs a path");
  expectOneLineError(run("run --backend nao --cameras socket:/" + std::string(120, 'x')), "--cameras", "at most 100");
  expectOneLineError(run("run --backend sim --cameras socket:/tmp/s"), "--cameras", "--backend sim");
}

TEST(Cli, NumbersAreBounded) {
  expectOneLineError(run("render --seed -1" + kOut), "--seed", "0..4294967295");
  expectOneLineError(run("render --seed 4294967296" + kOut), "--seed");
  expectOneLineError(run("eval walk --trials 99999999999"), "--trials");
  expectOneLineError(run("walk --seconds 1e30"), "--seconds", "0.1..3600 s");
  expectOneLineError(run("walk --seconds 1e-300"), "--seconds");
  expectOneLineError(run("walk --seconds nan"), "--seconds");
  expectOneLineError(run("render --head 1e30,0" + kOut), "--head", "YAW");
  expectOneLineError(run("render --head 0,35" + kOut), "--head", "PITCH");  // beyond HeadPitch's 29.5 deg
  // The pose against the field file: 5.3 m is beyond the standard field's border (5.2 m)...
  expectOneLineError(run("render --pose 5.3,0,0" + kOut), "--pose", "off this field");
  // ...and beyond the reduced field's much sooner.
  expectOneLineError(run("render --ball 4.6,0 --field " + std::string(NAO_SOURCE_DIR) + "/config/field_dimensions_reduced.json" + kOut),
                     "--ball");
}

// One error stays one line, whatever the input echoes.
TEST(Cli, ControlCharactersAreEscaped) {
  const Result r = run("render --lighting $'bo\ngus\x1b[31m'" + kOut);
  expectOneLineError(r, "--lighting", "\\n");
  EXPECT_EQ(r.out.find('\x1b'), std::string::npos) << r.out;
}

TEST(Cli, UnknownCommand) { expectOneLineError(run("fly"), "fly"); }

TEST(Cli, BadNumber) { expectOneLineError(run("render --pose 1,2" + kOut), "--pose", "3"); }

TEST(Cli, MissingFieldFile) { expectOneLineError(run("render --field /nonexistent/field.json" + kOut), "/nonexistent/field.json"); }

TEST(Cli, FieldFileMissingKey) {
  const auto path = tempFile("nolength.json", R"({"field": {"width": 6.0, "penaltyCrossSize": 0.1,
    "goalBoxAreaLength": 0.6, "goalBoxAreaWidth": 2.2, "penaltyAreaLength": 1.65, "penaltyAreaWidth": 4.0,
    "penaltyCrossDistance": 1.3, "centerCircleDiameter": 1.5, "borderStripWidth": 0.7},
    "goal": {"postDiameter": 0.1, "height": 0.8, "innerWidth": 1.5, "depth": 0.5}})");
  expectOneLineError(run("render --field " + path + kOut), path, "length");
}

TEST(Cli, FieldFileNegativeLength) {
  const auto path = tempFile("negative.json", R"({"field": {"length": -9.0, "width": 6.0, "penaltyCrossSize": 0.1,
    "goalBoxAreaLength": 0.6, "goalBoxAreaWidth": 2.2, "penaltyAreaLength": 1.65, "penaltyAreaWidth": 4.0,
    "penaltyCrossDistance": 1.3, "centerCircleDiameter": 1.5, "borderStripWidth": 0.7},
    "goal": {"postDiameter": 0.1, "height": 0.8, "innerWidth": 1.5, "depth": 0.5}})");
  expectOneLineError(run("render --field " + path + kOut), path, "field.length");
}

TEST(Cli, FieldFileMalformedJson) {
  const auto path = tempFile("broken.json", R"({"field": {"length": 9.0, )");
  expectOneLineError(run("render --field " + path + kOut), path);
}

TEST(Cli, MissingModel) { expectOneLineError(run("render --model /nonexistent/nao.xml" + kOut), "/nonexistent/nao.xml"); }

TEST(Cli, MalformedModel) {
  const auto path = tempFile("broken.xml", "<mujoco><worldbody><body name=\"torso\"><geom type=\"box\"</worldbody></mujoco>");
  expectOneLineError(run("render --model " + path + kOut), path);
}

TEST(Cli, ModelWithUnknownElement) {
  const auto path = tempFile("bad.xml", "<mujoco><worldbody><body name=\"torso\"><freejoint name=\"root\"/>"
                                        "<geom type=\"box\" size=\"0.1 0.1 0.1\"/><flux/></body></worldbody></mujoco>");
  expectOneLineError(run("render --model " + path + kOut), path);
}

TEST(Cli, BadLighting) { expectOneLineError(run("render --lighting intensity=-1" + kOut), "intensity"); }

TEST(Cli, BadMiscalibration) { expectOneLineError(run("render --miscalibration 1,2,3" + kOut), "--miscalibration"); }

TEST(Cli, TrainNeedsATarget) { expectOneLineError(run("train"), "train", "ball"); }

TEST(Cli, TrainTooFewScenes) { expectOneLineError(run("train ball --scenes 2"), "--scenes"); }

TEST(Cli, TrainCorruptSamples) {
  expectOneLineError(run("train ball --samples " + tempFile("samples.bin", "BSM1 but not really")), "samples.bin");
}

// A full disk is a failed run (exit 1) naming the file, and the picture the run had made is
// not left behind half a result.
TEST(Cli, FullDiskFailsAndLeavesNothing) {
  if (!std::ifstream("/dev/full")) GTEST_SKIP() << "no /dev/full";
  const std::string png = std::string(::testing::TempDir()) + "fulldisk.png";
  std::remove(png.c_str());
  const Result r = run("render --camera bottom --out " + png + " --json /dev/full");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_EQ(lines(r.out), 1) << r.out;
  EXPECT_NE(r.out.find("/dev/full"), std::string::npos) << r.out;
  EXPECT_FALSE(std::ifstream(png).good()) << png << " was left behind";
}

// Interrupted (Ctrl-C) halfway: the pictures written so far and the folder the run made are
// gone, not left as half a result.
TEST(Cli, InterruptedRunLeavesNothing) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(::testing::TempDir()) / "interrupted" / "images";
  fs::remove_all(dir.parent_path());
  const std::string cmd = std::string(NAO_BINARY) + " run --seconds 60 --images " + dir.string() +
                          " >/dev/null 2>&1 & pid=$!; sleep 4; kill -INT $pid; wait $pid; echo $?";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  char buf[64] = "";
  ASSERT_NE(fgets(buf, sizeof buf, p), nullptr);
  pclose(p);
  EXPECT_EQ(std::atoi(buf), 130) << "not ended by SIGINT: " << buf;  // 128 + SIGINT
  // The run made both folders; both are gone.
  EXPECT_FALSE(fs::exists(dir.parent_path())) << dir.parent_path() << " was left behind";
}

// MuJoCo's warnings go to stderr as one line: stdout carries the JSON alone, and no
// MUJOCO_LOG.TXT appears. A robot with 320 studs under its left sole overflows MuJoCo's contact
// buffer at the first step (a warning, not an error: the run goes on).
TEST(Cli, MujocoWarningKeepsJsonOnStdout) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(::testing::TempDir()) / "mujoco_warning";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string model = slurpFile(std::string(NAO_SOURCE_DIR) + "/models/nao_v6.xml");
  const std::string sole = "<geom name=\"LFoot_geom\"";
  const auto at = model.find(sole);
  ASSERT_NE(at, std::string::npos);
  std::string studs;
  for (int i = 0; i < 320; ++i) {
    char g[200];
    std::snprintf(g, sizeof g, "<geom type=\"sphere\" size=\"0.004\" pos=\"%.4f %.4f -0.0412\" mass=\"0.00001\"/>",
                  -0.04 + 0.12 * (i % 20) / 20, -0.035 + 0.08 * (i / 20) / 16);
    studs += g;
  }
  model.insert(model.find("/>", at) + 2, studs);
  std::ofstream((dir / "nao_studs.xml").string()) << model;
  const std::string cmd = "cd " + dir.string() + " && " + NAO_BINARY +
                          " run --model nao_studs.xml --seconds 0.5 --cameras off --json - 2>stderr.txt";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[4096];
  while (std::size_t n = fread(buf, 1, sizeof buf, p)) out.append(buf, n);
  EXPECT_EQ(pclose(p), 0);
  const auto json = nlohmann::json::parse(out, nullptr, false);
  EXPECT_FALSE(json.is_discarded()) << "stdout is not JSON:\n" << out;
  const std::string err = slurpFile((dir / "stderr.txt").string());
  EXPECT_NE(err.find("nao-soccer: MuJoCo warning: Pre-allocated contact buffer is full"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "MUJOCO_LOG.TXT"));
}

// `modules` lists the registry: every module config/modules.json uses (or the camera pipeline's
// config/camera_modules.json does) or that could take a used one's place (it provides the same:
// OracleVision for CameraVision), with its declarations.
TEST(Cli, ModulesListsTheRegistry) {
  const std::string path = std::string(::testing::TempDir()) + "modules.json";
  const Result r = run("modules --json " + path);
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = nlohmann::json::parse(slurpFile(path));
  const auto camera = nlohmann::json::parse(slurpFile(nao::dataPath("config/camera_modules.json"))).at("providers");
  const auto inCameraPipeline = [&](const nlohmann::json& name) {
    for (const auto& [rep, module] : camera.items())
      if (module == name) return true;
    return false;
  };
  const auto providers = nlohmann::json::parse(slurpFile(nao::dataPath("config/modules.json"))).at("providers");
  const auto alternative = [&](const nlohmann::json& m) {
    for (const auto& rep : m.at("provides"))
      if (providers.contains(rep.get<std::string>()) && providers.at(rep.get<std::string>()) != m.at("name")) return true;
    return false;
  };
  bool motion = false;
  for (const auto& m : j.at("modules")) {
    EXPECT_TRUE(m.at("used").get<bool>() || inCameraPipeline(m.at("name")) || alternative(m)) << m.dump();
    if (m.at("name") == "MotionEngine") {
      motion = true;
      EXPECT_EQ(m.at("cadence"), "motion");
      EXPECT_NE(m.at("provides").dump().find("JointRequest"), std::string::npos);
      EXPECT_NE(m.at("requires").dump().find("FallState"), std::string::npos);
    }
  }
  EXPECT_TRUE(motion);
  const Result dot = run("modules --dot");
  EXPECT_EQ(dot.code, 0);
  EXPECT_NE(dot.out.find("\"FallDetector\" -> \"MotionEngine\""), std::string::npos) << dot.out;
}

TEST(Cli, HelpExitsZero) {
  const Result r = run("render --help");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("--camera"), std::string::npos);
}

}  // namespace

namespace {

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

TEST(Cli, SameSeedSameImageAndJson) {
  const std::string dir = ::testing::TempDir();
  std::string outputs[3][2];
  const char* seeds[3] = {"5", "5", "6"};
  for (int i = 0; i < 3; ++i) {
    // The same output paths each time (the JSON names them), read back after each run.
    const std::string png = dir + "seed.png", json = dir + "seed.json";
    const Result r = run(std::string("render --camera bottom --pose -3.2,-3,90 --head 20,10 --miscalibration random "
                                     "--lighting noise=3 --seed ") + seeds[i] + " --out " + png + " --json " + json);
    ASSERT_EQ(r.code, 0) << r.out;
    outputs[i][0] = slurp(png);
    outputs[i][1] = slurp(json);
    ASSERT_GT(outputs[i][0].size(), 1000u);
  }
  EXPECT_EQ(outputs[0][0], outputs[1][0]);
  EXPECT_EQ(outputs[0][1], outputs[1][1]);
  EXPECT_NE(outputs[0][0], outputs[2][0]);  // another seed: other noise and other offsets
  EXPECT_NE(outputs[0][1], outputs[2][1]);
}

TEST(Cli, SameSeedSameRun) {
  const std::string dir = ::testing::TempDir();
  std::string json[2], image[2];
  for (int i = 0; i < 2; ++i) {
    const std::string out = dir + "run";
    const Result r = run("run --backend sim --seconds 1.2 --seed 3 --lighting noise=2 --images " + out + " --json " + out + ".json");
    ASSERT_EQ(r.code, 0) << r.out;
    json[i] = slurp(out + ".json");
    image[i] = slurp(out + "/top_001.png");
    ASSERT_GT(image[i].size(), 1000u);
  }
  EXPECT_EQ(json[0], json[1]);
  EXPECT_EQ(image[0], image[1]);
}

}  // namespace
