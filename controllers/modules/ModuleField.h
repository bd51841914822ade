#pragma once
// The field a module works on: the run's field file (RobotProgramConfig::field, handed to the
// modules as context.params["FieldDimensions"]), else field_dimensions.json in the
// configuration folder.
#include <any>
#include <string>

#include "perception/FieldDimensions.h"
#include "robot/Parameters.h"
#include "robot/Paths.h"

namespace nao::modules {

inline const char* kFieldParams = "FieldDimensions";

inline FieldDimensions fieldFor(const ModuleContext& context) {
  if (auto it = context.params.find(kFieldParams); it != context.params.end())
    if (const auto* f = std::any_cast<FieldDimensions>(&it->second)) return *f;
  const std::string dir = context.configDir.empty() ? dataPath("config") : context.configDir;
  return FieldDimensions::load(dir + "/field_dimensions.json");
}

}  // namespace nao::modules
