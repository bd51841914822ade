#pragma once
// The simulator's settings from the parsed options: field, lighting, injected miscalibration.
#include <nlohmann/json.hpp>

#include "apps/cli/Options.h"
#include "perception/CameraCalibration.h"
#include "perception/FieldDimensions.h"
#include "sim/Lighting.h"
#include "sim/VenueLook.h"

namespace nao::cli {

// The field file given with --field (or `fallback`), with every declared place checked on it.
FieldDimensions fieldFrom(const CommonOptions& common, const std::string& fallback = "config/field_dimensions.json");
sim::Lighting lightingFrom(const std::string& spec);
// --venue: none, random or a name of config/venues.json (sim/VenueLook.h).
sim::VenueChoice venueFrom(const std::string& venue);
// What an evaluation drew its venues from: the choice and every look it could take.
nlohmann::json venueJson(const sim::VenueChoice& venue);
// fieldFrom for the commands that look at the goal box: a field file without one is refused.
FieldDimensions calibrationFieldFrom(const CommonOptions& common);
// "sweep" (every preset of the sweep) or one lighting.
std::vector<sim::Lighting> lightingsFrom(const std::string& spec);
// Compiles the scene with the robot model `model` ("" = the default, not checked): a broken
// model file is refused before a run prints anything.
void checkRobotModel(const std::string& model, const FieldDimensions& field);
CameraCalibration miscalibrationFrom(const SimOptions& sim, std::uint64_t seed);
nlohmann::json calibrationDegJson(const CameraCalibration& c);
nlohmann::json lightingJson(const sim::Lighting& l);
// The camera model's loops after an image (sim/CameraSensor.h): exposure, gain, white balance.
nlohmann::json cameraExposureJson(const sim::CameraExposure& e);

}  // namespace nao::cli
