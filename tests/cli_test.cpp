// The nao-soccer command: bad input exits 2 with one line naming the file/flag and the problem.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <string>

#include "support/RunCommand.h"

namespace {

using Result = nao::test::CommandResult;

Result run(const std::string& args) { return nao::test::runCommand(args); }

std::string tempFile(const std::string& name, const std::string& content) {
  const std::string path = std::string(::testing::TempDir()) + name;
  std::ofstream(path) << content;
  return path;
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

TEST(Cli, UnknownFlag) { expectOneLineError(run("render --camera top --frobnicate 3" + kOut), "--frobnicate", "unknown option"); }

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
