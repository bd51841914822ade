// The registry of modules, config/modules.json and the robot program built from them: every
// module listed with its declarations, a provider swapped by configuration, bad files as one
// line naming file and key, the Graphviz graph.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "controllers/RobotProgram.h"
#include "robot/Error.h"
#include "robot/ModuleRegistry.h"
#include "robot/Paths.h"

namespace nao {

// A stand-in provider, as a scenario's oracle would be: registered like any module.
class FallOracle : public Module<FallOracle, Requires<SensorFrame>, Provides<FallState>> {
 public:
  explicit FallOracle(const ModuleContext&) {}

 private:
  void update() override { out<FallState>().fallen = in<SensorFrame>().time > 1.0; }
};
NAO_REGISTER_MODULE(FallOracle);

namespace {

const ModuleInfo* findInfo(const std::vector<ModuleInfo>& all, const std::string& name) {
  auto it = std::find_if(all.begin(), all.end(), [&](const ModuleInfo& m) { return m.name == name; });
  return it == all.end() ? nullptr : &*it;
}

using Names = std::vector<std::string>;

TEST(ModuleRegistry, ListsEveryModuleWithItsDeclarations) {
  const auto all = registeredModules();
  for (const char* name : {"TorsoMatrixProvider", "CameraMatrixProvider", "FallDetector", "HeadControl", "MotionEngine"})
    ASSERT_NE(findInfo(all, name), nullptr) << name << " is not registered (or not linked)";
  const ModuleInfo& camera = *findInfo(all, "CameraMatrixProvider");
  EXPECT_EQ(camera.required, (Names{"SensorFrame", "TorsoState", "CameraCalibration", "CameraImages"}));
  EXPECT_EQ(camera.provided, (Names{"CameraMatrices"}));
  EXPECT_EQ(camera.cadence, Cadence::Motion);
  const ModuleInfo& motion = *findInfo(all, "MotionEngine");
  EXPECT_EQ(motion.required, (Names{"SensorFrame", "FallState", "MotionRequest", "HeadJointRequest", "ArmMotionRequest"}));
  EXPECT_EQ(motion.provided, (Names{"JointRequest", "MotionInfo", "Odometry"}));
  EXPECT_EQ(findInfo(all, "HeadControl")->required, (Names{"SensorFrame", "HeadMotionRequest", "TorsoState"}));
  // Sorted by name, each once.
  EXPECT_TRUE(std::is_sorted(all.begin(), all.end(), [](auto& a, auto& b) { return a.name < b.name; }));
  for (const auto& m : all) {
    const auto module = createModule(m.name);
    EXPECT_EQ(module->name(), m.name);
  }
  try {
    createModule("Nope");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "module Nope: not registered (controllers/modules/Nope.cpp?)");
  }
}

TEST(ModuleRegistry, CommittedModulesJson) {
  const ProviderMap p = loadProviders(dataPath("config/modules.json"));
  EXPECT_EQ(p.at("FallState"), "FallDetector");
  EXPECT_EQ(chosenModules(p), (Names{"AutoExposureWeighting", "BallLocator", "BallTracker", "BehaviorControl", "ButtonStateProvider", "Calibrator",
                                     "CameraCalibrationProvider",
                                     "CameraMatrixProvider",
                                     "CameraVision", "ChallengeModeProvider", "ExposureCameraMatrixProvider", "FallDetector", "FieldBallLocator",
                                     "FrameHistoryProvider", "GameStateProvider", "HeadControl", "LedControl", "MotionEngine", "OwnBodyProvider",
                                     "SelfLocalization", "TorsoMatrixProvider"}));
}

std::string providersError(const std::string& text) {
  try {
    parseProviders(text, "modules.json");
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), "modules.json");
    return e.what();
  }
  return "";
}

TEST(ModuleRegistry, ArchitectureDocListsEveryProvider) {
  std::ifstream in(dataPath("docs/architecture.md"));
  std::stringstream doc;
  doc << in.rdbuf();
  const auto all = registeredModules();
  for (const auto& [rep, module] : loadProviders(dataPath("config/modules.json"))) {
    const std::string row = "| `" + rep + "` | `" + module + "` | " + cadenceName(findInfo(all, module)->cadence) + " |";
    EXPECT_NE(doc.str().find(row), std::string::npos) << "docs/architecture.md lacks the row " << row;
  }
}

TEST(ModuleRegistry, BadModulesJsonIsOneLineNamingTheKey) {
  EXPECT_NE(providersError(R"({"providers": {)").find("modules.json: not valid JSON: parse error"), std::string::npos);
  EXPECT_EQ(providersError("[]"), "modules.json: must be a JSON object with \"providers\"");
  EXPECT_EQ(providersError("{}"), "modules.json: providers: missing");
  EXPECT_EQ(providersError(R"({"provider": {}})"), "modules.json: provider: unknown key");
  EXPECT_EQ(providersError(R"({"providers": []})"), "modules.json: providers: must be an object (representation -> module)");
  EXPECT_EQ(providersError(R"({"providers": {"FallState": 3}})"), "modules.json: providers.FallState: must be a module name (a string)");
  EXPECT_EQ(providersError(R"({"providers": {"FallStat": "FallDetector"}})"),
            "modules.json: providers.FallStat: unknown representation (no registered module provides it)");
  EXPECT_EQ(providersError(R"({"providers": {"FallState": "FallDetektor"}})"),
            "modules.json: providers.FallState: unknown module \"FallDetektor\"");
  EXPECT_EQ(providersError(R"({"providers": {"Odometry": "FallDetector"}})"),
            "modules.json: providers.Odometry: module FallDetector does not provide Odometry");
  EXPECT_EQ(providersError(R"({"providers": {"Odometry": "MotionEngine"}})"),
            "modules.json: providers.JointRequest: missing (MotionEngine, chosen for another representation, provides it)");
  EXPECT_EQ(providersError(R"({"providers": {"FallState": "FallDetector", "Odo\nmetry": "x"}})"),
            "modules.json: providers.Odo\\nmetry: unknown representation (no registered module provides it)");
}

TEST(RobotProgram, OrderFollowsTheDeclarations) {
  RobotProgram program;
  // Motion in dependency order, then cognition.
  EXPECT_EQ(program.moduleOrder(),
            (Names{"ButtonStateProvider", "CameraCalibrationProvider", "TorsoMatrixProvider", "CameraMatrixProvider",
                   "ChallengeModeProvider",
                   "FallDetector", "HeadControl",
                   "MotionEngine", "FrameHistoryProvider", "GameStateProvider", "LedControl",
                   "ExposureCameraMatrixProvider", "OwnBodyProvider", "AutoExposureWeighting", "CameraVision", "SelfLocalization", "BallLocator", "BallTracker", "FieldBallLocator",
                   "BehaviorControl", "Calibrator"}));
}

TEST(RobotProgram, AProviderRemovedByConfigurationBecomesAnInput) {
  RobotProgramConfig config;
  config.withoutBehavior();
  const Names order = RobotProgram(config).moduleOrder();
  EXPECT_EQ(std::find(order.begin(), order.end(), "BehaviorControl"), order.end());
  EXPECT_NE(std::find(order.begin(), order.end(), "SelfLocalization"), order.end());
  config.providers = {{"Nonsense", ""}};
  try {
    RobotProgram program(config);
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "RobotProgramConfig.providers: providers.Nonsense: has no provider to remove");
  }
}

TEST(RobotProgram, AProviderSwappedByConfiguration) {
  RobotProgramConfig config;
  config.providers = {{"FallState", "FallOracle"}};
  RobotProgram program(config);
  const auto order = program.moduleOrder();
  EXPECT_NE(std::find(order.begin(), order.end(), "FallOracle"), order.end());
  EXPECT_EQ(std::find(order.begin(), order.end(), "FallDetector"), order.end());
  config.providers = {{"FallState", "FallOracle"}, {"JointRequest", "FallOracle"}};
  try {
    RobotProgram bad(config);
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "RobotProgramConfig.providers: providers.JointRequest: module FallOracle does not provide JointRequest");
  }
}

TEST(RobotProgram, BadModulesJsonInTheConfigFolder) {
  const auto dir = std::filesystem::temp_directory_path() / "nao_modules_json_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "modules.json") << R"({"providers": {"FallState": "Nobody"}})";
  RobotProgramConfig config;
  config.configDir = dir.string();
  try {
    RobotProgram program(config);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "modules.json").string() + ": providers.FallState: unknown module \"Nobody\"");
  }
  // A config with a missing provider: the pipeline names who needs what.
  std::ofstream(dir / "modules.json") << R"({"providers": {"FallState": "FallDetector", "JointRequest": "MotionEngine",
      "MotionInfo": "MotionEngine", "Odometry": "MotionEngine"}})";
  try {
    RobotProgram program(config);
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "module pipeline: MotionEngine requires HeadJointRequest, which no module provides and no input is");
  }
  std::filesystem::remove_all(dir);
}

TEST(ModuleRegistry, GraphvizDot) {
  std::ostringstream dot;
  writeModuleGraphDot(dot, registeredModules(), loadProviders(dataPath("config/modules.json")));
  const std::string s = dot.str();
  EXPECT_EQ(s.rfind("digraph modules {", 0), 0u);
  EXPECT_NE(s.find("\"TorsoMatrixProvider\" -> \"CameraMatrixProvider\" [label=\"TorsoState\"];"), std::string::npos) << s;
  EXPECT_NE(s.find("\"FallDetector\" -> \"MotionEngine\" [label=\"FallState\"];"), std::string::npos);
  EXPECT_NE(s.find("\"input:SensorFrame\" -> \"FallDetector\";"), std::string::npos);
  EXPECT_NE(s.find("subgraph cluster_motion"), std::string::npos);
  EXPECT_EQ(s.find("FallOracle"), std::string::npos);  // not chosen
  std::ostringstream all;
  writeModuleGraphDot(all, registeredModules());
  EXPECT_NE(all.str().find("FallOracle"), std::string::npos);
}

}  // namespace
}  // namespace nao
