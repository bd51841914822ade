#include "controllers/RobotProgram.h"


#include "robot/ModuleRegistry.h"
#include "robot/Paths.h"

namespace nao {

std::string RobotProgramConfig::defaultConfigDir() { return dataPath("config"); }

RobotProgram::RobotProgram(const RobotProgramConfig& config) {
  const std::string dir = config.configDir.empty() ? RobotProgramConfig::defaultConfigDir() : config.configDir;
  ProviderMap providers = loadProviders(dir + "/modules.json");
  overrideProviders(providers, config.providers, "RobotProgramConfig.providers");

  ModuleContext context;
  if (!config.configDir.empty()) context.configDir = config.configDir;
  context.headId = config.headId;
  if (config.motion) context.params["MotionEngine"] = *config.motion;

  blackboard_.write<CameraCalibration>() = config.calibration;
  blackboard_.write<MotionRequest>() = MotionRequest{};  // stand
  blackboard_.write<HeadMotionRequest>() = HeadMotionRequest{};
  // What the cycle writes (backend) and what the app sets (calibration) are inputs; the
  // behaviour's requests too, as long as no module provides them (scenarios and tests write them).
  pipeline_.inputs<SensorFrame, CameraImages, CameraCalibration>();
  if (!providers.count(typeName<MotionRequest>())) pipeline_.inputs<MotionRequest>();
  if (!providers.count(typeName<HeadMotionRequest>())) pipeline_.inputs<HeadMotionRequest>();
  for (const std::string& name : chosenModules(providers)) pipeline_.add(createModule(name, context));
  pipeline_.sort();
}

bool RobotProgram::cycle(Backend& backend) {
  auto& frame = blackboard_.write<SensorFrame>();
  if (!backend.waitForSensors(frame)) return false;
  auto& images = blackboard_.write<CameraImages>();
  for (CameraId cam : {CameraId::Top, CameraId::Bottom}) {
    CameraImage img;
    auto& slot = images.latest[static_cast<int>(cam)];
    if (backend.takeImage(cam, img))
      slot = std::move(img);
    else
      slot.reset();
  }
  pipeline_.update(blackboard_);
  backend.sendRequest(blackboard_.read<JointRequest>(), blackboard_.write<LedRequest>());
  return true;
}

}  // namespace nao
