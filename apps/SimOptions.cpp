#include "apps/SimOptions.h"

#include <cmath>
#include <random>

#include <mujoco/mujoco.h>

#include "robot/Error.h"
#include "robot/Paths.h"
#include "sim/SceneBuilder.h"

namespace nao::cli {

FieldDimensions fieldFrom(const CommonOptions& common, const std::string& fallback) {
  const FieldDimensions field = FieldDimensions::load(common.field.empty() ? dataPath(fallback) : common.field);
  checkPlaces(common, field);
  return field;
}

sim::Lighting lightingFrom(const std::string& spec) {
  return sim::Lighting::parse(spec, dataPath("config/lighting.json"));
}

sim::VenueChoice venueFrom(const std::string& venue) {
  return sim::VenueChoice::load(venue, dataPath("config/venues.json"));
}

nlohmann::json venueJson(const sim::VenueChoice& venue) {
  nlohmann::json looks = nlohmann::json::array();
  if (venue.venue == "random")
    for (const sim::VenueLook& l : venue.looks) looks.push_back(sim::toJson(l));
  else
    looks.push_back(sim::toJson(venue.forSeed(0)));
  return {{"choice", venue.venue}, {"looks", looks}};
}

std::vector<sim::Lighting> lightingsFrom(const std::string& spec) {
  const std::string file = dataPath("config/lighting.json");
  if (spec == "sweep") return sim::Lighting::sweep(file);
  if (spec.rfind("sweep,", 0) == 0) return sim::Lighting::sweep(file, spec.substr(6));
  return {sim::Lighting::parse(spec, file)};
}

void checkRobotModel(const std::string& model, const FieldDimensions& field) {
  if (model.empty()) return;
  sim::SceneSpec spec;
  spec.field = field;
  spec.robotModel = model;
  mj_deleteModel(sim::compileScene(spec));
}

CameraCalibration miscalibrationFrom(const SimOptions& sim, std::uint64_t seed) {
  std::array<double, 6> a{};
  if (sim.miscalibration == "none") return {};
  if (sim.miscalibration == "random") {
    std::mt19937_64 rng(seed * 7919 + 17);
    std::uniform_real_distribution<double> u(-3, 3);
    for (double& v : a) v = u(rng) * M_PI / 180;
    return CameraCalibration::fromArray(a);
  }
  for (int i = 0; i < 6; ++i) a[i] = sim.miscalibrationDeg.at(i) * M_PI / 180;
  return CameraCalibration::fromArray(a);
}

nlohmann::json calibrationDegJson(const CameraCalibration& c) {
  nlohmann::json j;
  const auto a = c.toArray();
  for (int i = 0; i < 6; ++i) j[CameraCalibration::kNames[i]] = a[i] * 180 / M_PI;
  return j;
}

nlohmann::json lightingJson(const sim::Lighting& l) {
  return {{"name", l.name},          {"intensity", l.intensity}, {"temperature", l.temperature},
          {"shadows", l.shadows},    {"elevation", l.elevation}, {"azimuth", l.azimuth},
          {"ambient", l.ambient},    {"noise", l.noise},
          {"camera",
           {{"enabled", l.camera.enabled},
            {"ae", l.camera.autoExposure},
            {"awb", l.camera.autoWhiteBalance},
            {"vignetting", l.camera.vignetting},
            {"defocus", l.camera.defocus},
            {"motion", l.camera.motion}}}};
}

nlohmann::json cameraExposureJson(const sim::CameraExposure& e) {
  return {{"exposure_ms", e.exposureMs},
          {"gain", e.gain},
          {"white_balance", {e.whiteBalance[0], e.whiteBalance[1], e.whiteBalance[2]}},
          {"metered_luma", e.meteredLuma}};
}

// The calibration looks at the goal box: a field file without one is bad input for it.
FieldDimensions calibrationFieldFrom(const CommonOptions& common) {
  FieldDimensions f = fieldFrom(common);
  if (!f.hasGoalBox)
    throw Error(common.field.empty() ? dataPath("config/field_dimensions.json") : common.field,
                "field.goalBoxAreaLength/goalBoxAreaWidth: missing, and the calibration looks at the goal box");
  return f;
}

}  // namespace nao::cli
