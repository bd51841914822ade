// nao-soccer modules: the robot program's modules from the registry (robot/ModuleRegistry.h),
// with what each requires and provides and which config/modules.json chooses; --dot draws it.
// Then the debug channels (robot/Debug.h) that --debug can subscribe.
#include <cstdio>
#include <set>
#include <sstream>

#include "apps/Cli.h"
#include "apps/Commands.h"
#include "robot/ModuleRegistry.h"
#include "robot/OutputFiles.h"
#include "robot/Paths.h"

namespace nao::cli {

namespace {

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s.empty() ? "-" : s;
}

}  // namespace

int modulesCommand(const ModulesOptions& options) {
  const std::vector<ModuleInfo> modules = registeredModules();
  const ProviderMap providers = loadProviders(dataPath("config/modules.json"));
  // In use: chosen by the robot program (config/modules.json) or by each camera's vision
  // pipeline (config/camera_modules.json).
  std::set<std::string> inUse;
  for (const std::string& file : {std::string("config/modules.json"), std::string("config/camera_modules.json")})
    for (const auto& name : chosenModules(loadProviders(dataPath(file)))) inUse.insert(name);
  if (options.dot) {
    std::ostringstream dot;
    writeModuleGraphDot(dot, modules, providers);
    std::fputs(dot.str().c_str(), stdout);
  } else if (options.common.json != "-") {
    std::printf("%-22s %-10s %-4s %-50s %s\n", "module", "cadence", "used", "requires", "provides");
    for (const auto& m : modules)
      std::printf("%-22s %-10s %-4s %-50s %s\n", m.name.c_str(), cadenceName(m.cadence),
                  inUse.count(m.name) ? "yes" : "no", joined(m.required).c_str(), joined(m.provided).c_str());
    std::printf("\n%-22s %s\n", "debug channel", "what --debug CHANNEL writes (JSON lines)");
    for (const DebugChannelInfo& c : debugChannelList()) std::printf("%-22s %s\n", c.name.c_str(), c.description.c_str());
  }
  if (!options.common.json.empty()) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& m : modules)
      list.push_back({{"name", m.name},
                      {"cadence", cadenceName(m.cadence)},
                      {"requires", m.required},
                      {"provides", m.provided},
                      {"used", inUse.count(m.name) != 0}});
    nlohmann::json channels = nlohmann::json::array();
    for (const DebugChannelInfo& c : debugChannelList())
      channels.push_back({{"name", c.name}, {"description", c.description}});
    writeJson(options.common.json, {{"modules", list}, {"providers", providers}, {"debug_channels", channels}});
  }
  return 0;
}

}  // namespace nao::cli
