#pragma once
// Options shared by the simulator subcommands: field, lighting, injected miscalibration.
#include "apps/Cli.h"
#include "perception/CameraCalibration.h"
#include "perception/FieldDimensions.h"
#include "sim/Lighting.h"

namespace nao::cli {

std::vector<Option> simOptions();
FieldDimensions fieldFrom(const Args& args);
std::string robotModelFrom(const Args& args);
sim::Lighting lightingFrom(const Args& args);
// --miscalibration none|random|B_ROLL,B_PITCH,T_ROLL,T_PITCH,B2_ROLL,B2_PITCH (deg).
CameraCalibration miscalibrationFrom(const Args& args, std::uint64_t seed);
nlohmann::json calibrationDegJson(const CameraCalibration& c);
nlohmann::json lightingJson(const sim::Lighting& l);

}  // namespace nao::cli
