// Parameters from files: the committed files hold today's defaults, a per-robot overlay
// changes only what it names, and every bad file is one nao::Error naming the file and key.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "controllers/modules/BallLocator.h"
#include "controllers/modules/BallTracker.h"
#include "controllers/modules/BehaviorControl.h"
#include "controllers/modules/FallDetector.h"
#include "controllers/modules/HeadControl.h"
#include "controllers/modules/MotionEngineParams.h"
#include "controllers/modules/SelfLocalization.h"
#include "perception/ExposureWeighting.h"
#include "perception/OwnBody.h"
#include "perception/vision/Denoise.h"
#include "robot/Error.h"
#include "robot/Parameters.h"
#include "robot/Paths.h"

namespace nao {
namespace {

struct Inner {
  double gain = 0.5;
};
struct Sample {
  double speed = 1.0;
  int count = 3;
  bool enabled = true;
  std::string mode = "fast";
  Inner inner;
};
template <class V>
void describe(V& v, Inner& p) {
  v("gain", p.gain, 0.0, 1.0);
}
template <class V>
void describe(V& v, Sample& p) {
  v("speed", p.speed, 0.0, 10.0);
  v("count", p.count, 1, 100);
  v("enabled", p.enabled);
  v("mode", p.mode, {"fast", "slow"});
  v("inner", p.inner);
}

std::string errorOf(const std::string& text) {
  Sample s;
  try {
    applyParamsText(text, "sample.json", s);
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), "sample.json");
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    return what;
  }
  return "";
}

TEST(Parameters, ReadsKnownKeysAndKeepsTheRest) {
  Sample s;
  applyParamsText(R"({"speed": 2.5, "inner": {"gain": 0.25}})", "sample.json", s);
  EXPECT_EQ(s.speed, 2.5);
  EXPECT_EQ(s.inner.gain, 0.25);
  EXPECT_EQ(s.count, 3);
  EXPECT_TRUE(s.enabled);
  applyParamsText(R"({"count": 7, "enabled": false, "speed": 0})", "sample.json", s);
  EXPECT_EQ(s.count, 7);
  EXPECT_FALSE(s.enabled);
  EXPECT_EQ(s.speed, 0.0);
}

TEST(Parameters, MalformedJson) {
  EXPECT_EQ(errorOf("{\"speed\": 1,").rfind("sample.json: not valid JSON: parse error at line 1, column 13", 0), 0u)
      << errorOf("{\"speed\": 1,");
  EXPECT_NE(errorOf("").find("not valid JSON"), std::string::npos);
  EXPECT_NE(errorOf("{\"speed\": NaN}").find("not valid JSON"), std::string::npos);
  EXPECT_NE(errorOf("{\"speed\": 1}\n{}").find("not valid JSON"), std::string::npos);
  EXPECT_EQ(errorOf("[1, 2]"), "sample.json: must be a JSON object of parameters");
  EXPECT_EQ(errorOf("null"), "sample.json: must be a JSON object of parameters");
}

TEST(Parameters, UnknownKeysAnywhere) {
  EXPECT_EQ(errorOf(R"({"sped": 1})"), "sample.json: sped: unknown parameter");
  EXPECT_EQ(errorOf(R"({"inner": {"gian": 1}})"), "sample.json: inner.gian: unknown parameter");
}

TEST(Parameters, WrongTypes) {
  EXPECT_EQ(errorOf(R"({"speed": "fast"})"), "sample.json: speed: must be a number");
  EXPECT_EQ(errorOf(R"({"speed": true})"), "sample.json: speed: must be a number");
  EXPECT_EQ(errorOf(R"({"speed": null})"), "sample.json: speed: must be a number");
  EXPECT_EQ(errorOf(R"({"speed": [1]})"), "sample.json: speed: must be a number");
  EXPECT_EQ(errorOf(R"({"count": 2.5})"), "sample.json: count: must be an integer");
  EXPECT_EQ(errorOf(R"({"enabled": 1})"), "sample.json: enabled: must be true or false");
  EXPECT_EQ(errorOf(R"({"inner": 3})"), "sample.json: inner: must be an object");
  EXPECT_EQ(errorOf(R"({"speed": "NaN"})"), "sample.json: speed: must be a number");
  EXPECT_EQ(errorOf(R"({"mode": "medium"})"), "sample.json: mode: must be one of fast, slow, not 'medium'");
  EXPECT_EQ(errorOf(R"({"mode": 2})"), "sample.json: mode: must be one of fast, slow");
  EXPECT_EQ(errorOf(R"({"mode": "slow"})"), "");
}

TEST(Parameters, NotFiniteAndOutOfRange) {
  // The parser refuses a number beyond double's range; the loader would refuse infinity too.
  EXPECT_EQ(errorOf(R"({"speed": 1e999})"), "sample.json: not valid JSON: number overflow parsing '1e999'");
  EXPECT_EQ(errorOf(R"({"speed": -1e999})"), "sample.json: not valid JSON: number overflow parsing '-1e999'");
  Sample s;
  nlohmann::json inf = nlohmann::json::object();
  inf["speed"] = std::numeric_limits<double>::infinity();
  try {
    applyParams(inf, "sample.json", s);
    ADD_FAILURE() << "infinity accepted";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "sample.json: speed: must be finite");
  }
  inf["speed"] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(applyParams(inf, "sample.json", s), Error);
  EXPECT_EQ(s.speed, 1.0);
  EXPECT_EQ(errorOf(R"({"speed": 1e308})"), "sample.json: speed: 1e+308 is out of range [0, 10]");
  EXPECT_EQ(errorOf(R"({"speed": -0.5})"), "sample.json: speed: -0.5 is out of range [0, 10]");
  EXPECT_EQ(errorOf(R"({"inner": {"gain": 1.5}})"), "sample.json: inner.gain: 1.5 is out of range [0, 1]");
  EXPECT_EQ(errorOf(R"({"count": 0})"), "sample.json: count: 0 is out of range [1, 100]");
  EXPECT_EQ(errorOf(R"({"count": 18446744073709551615})"),
            "sample.json: count: 18446744073709551615 is out of range [1, 100]");
  EXPECT_EQ(errorOf(R"({"count": -9223372036854775808})"),
            "sample.json: count: -9223372036854775808 is out of range [1, 100]");
  // A failed file leaves nothing half-applied that matters: the error stops the start.
}

TEST(Parameters, CommittedFilesHoldTodaysDefaults) {
  const std::string dir = dataPath("config");
  const auto same = [&](const std::string& module, const nlohmann::ordered_json& defaults) {
    const auto file = readJsonFile(parameterFile(dir, module));
    ASSERT_TRUE(file) << module;
    EXPECT_EQ(*file, nlohmann::json::parse(defaults.dump())) << module << ": the file differs from the defaults in code";
  };
  same("FallDetector", paramsToJson(FallDetector::Params{}));
  same("HeadControl", paramsToJson(HeadControl::Params{}));
  same("MotionEngine", paramsToJson(MotionEngine::Params{}));
  same("SelfLocalization", paramsToJson(modules::SelfLocalization::Params{}));
  same("BallLocator", paramsToJson(modules::BallLocator::Params{}));
  same("BehaviorControl", paramsToJson(modules::BehaviorControl::Params{}));
  same("BallTracker", paramsToJson(modules::BallTracker::Params{}));
  same("OwnBodyProvider", paramsToJson(OwnBodyParams{}));
  same("AutoExposureWeighting", paramsToJson(ExposureWeightingParams{}));
  same("ImageDenoiser", paramsToJson(DenoiseParams{}));
  // And they load without complaint to the same values.
  const auto m = loadParams<MotionEngine::Params>("MotionEngine", dir);
  EXPECT_EQ(paramsToJson(m), paramsToJson(MotionEngine::Params{}));
}

class ConfigDir : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("nao_params_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_ / "parameters");
    std::filesystem::create_directories(dir_ / "robots" / "head42");
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  void write(const std::string& rel, const std::string& text) { std::ofstream(dir_ / rel) << text; }
  std::string dir() const { return dir_.string(); }
  std::filesystem::path dir_;
};

TEST_F(ConfigDir, MissingFilesKeepDefaultsAndTheOverlayWinsPerKey) {
  EXPECT_EQ(loadParams<HeadControl::Params>("HeadControl", dir()).maxYawSpeed, HeadControl::Params{}.maxYawSpeed);
  write("parameters/HeadControl.json", R"({"maxYawSpeed": 2.0, "maxPitchSpeed": 1.5})");
  write("robots/head42/HeadControl.json", R"({"maxYawSpeed": 1.0})");
  const auto base = loadParams<HeadControl::Params>("HeadControl", dir());
  EXPECT_EQ(base.maxYawSpeed, 2.0);
  const auto robot = loadParams<HeadControl::Params>("HeadControl", dir(), "head42");
  EXPECT_EQ(robot.maxYawSpeed, 1.0);
  EXPECT_EQ(robot.maxPitchSpeed, 1.5);
  EXPECT_EQ(robot.maxAcceleration, HeadControl::Params{}.maxAcceleration);
  // Another robot has no overlay.
  EXPECT_EQ(loadParams<HeadControl::Params>("HeadControl", dir(), "head7").maxYawSpeed, 2.0);
}

TEST_F(ConfigDir, ErrorsNameTheFileAndTheKey) {
  write("robots/head42/MotionEngine.json", R"({"walk": {"stepDuration": "0.25"}})");
  try {
    loadParams<MotionEngine::Params>("MotionEngine", dir(), "head42");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), dir() + "/robots/head42/MotionEngine.json: walk.stepDuration: must be a number");
  }
  write("parameters/FallDetector.json", R"({"fallenAngle": 0.84, "falenAngle": 1})");
  try {
    loadParams<FallDetector::Params>("FallDetector", dir());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), dir() + "/parameters/FallDetector.json: falenAngle: unknown parameter");
  }
  EXPECT_THROW(loadParams<FallDetector::Params>("FallDetector", dir(), "../etc"), Error);
}

TEST_F(ConfigDir, ContextOverridesFilesAndChecksTheType) {
  write("parameters/FallDetector.json", R"({"fallenAngle": 1.0})");
  ModuleContext context{dir(), "", {}};
  EXPECT_EQ(context.load<FallDetector::Params>("FallDetector").fallenAngle, 1.0);
  FallDetector::Params p;
  p.fallenAngle = 0.7;
  context.params["FallDetector"] = p;
  EXPECT_EQ(context.load<FallDetector::Params>("FallDetector").fallenAngle, 0.7);
  EXPECT_THROW(context.load<HeadControl::Params>("FallDetector"), Error);
  EXPECT_EQ(ModuleContext{}.load<FallDetector::Params>("FallDetector").fallenAngle, FallDetector::Params{}.fallenAngle);
}

}  // namespace
}  // namespace nao
