#include "apps/SimOptions.h"

#include <cmath>
#include <random>

#include "robot/Error.h"
#include "robot/Paths.h"

namespace nao::cli {

std::vector<Option> simOptions() {
  return {{"lighting", "SPEC", "preset (default, bright, dark, warm, cold, shadows) or key=value list"},
          {"miscalibration", "SPEC", "injected offsets: none, random, or 6 numbers in deg"},
          {"model", "FILE", "the robot's MJCF (default models/nao_v6.xml)"}};
}

FieldDimensions fieldFrom(const Args& args) {
  return FieldDimensions::load(args.str("field", dataPath("config/field_dimensions.json")));
}

std::string robotModelFrom(const Args& args) { return args.str("model", ""); }

sim::Lighting lightingFrom(const Args& args) {
  return sim::Lighting::parse(args.str("lighting", "default"), dataPath("config/lighting.json"));
}

CameraCalibration miscalibrationFrom(const Args& args, std::uint64_t seed) {
  const std::string spec = args.str("miscalibration", "none");
  if (spec == "none") return {};
  std::array<double, 6> a{};
  if (spec == "random") {
    std::mt19937_64 rng(seed * 7919 + 17);
    std::uniform_real_distribution<double> u(-3, 3);
    for (double& v : a) v = u(rng) * M_PI / 180;
    return CameraCalibration::fromArray(a);
  }
  const auto v = args.list("miscalibration", 6);
  for (int i = 0; i < 6; ++i) {
    if (std::abs(v[i]) > 20) throw Error("--miscalibration", "offsets beyond +-20 deg are not a miscalibration");
    a[i] = v[i] * M_PI / 180;
  }
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
          {"ambient", l.ambient},    {"noise", l.noise}};
}

}  // namespace nao::cli
