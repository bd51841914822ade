#include "scenarios/Venue.h"


#include <nlohmann/json.hpp>

#include "robot/Error.h"
#include "scenarios/CalibrationChallenge.h"

namespace nao::sim {

std::vector<Venue> loadVenues(const std::string& path, const FieldDimensions& field) {
  const nlohmann::json j = readVenueFile(path);
  std::vector<Venue> venues;
  for (std::size_t i = 0; i < j["venues"].size(); ++i) {
    const nlohmann::json& v = j["venues"][i];
    const std::string where = "venues[" + std::to_string(i) + "]";
    for (const auto& [key, value] : v.items())
      if (key != "name" && key != "floor_friction" && key != "balls" && key != "look") throw Error(path, where + "." + key + ": unknown key");
    Venue venue;
    venue.name = v["name"];
    if (!v.contains("floor_friction") || !v["floor_friction"].is_number() || !(v["floor_friction"].get<double>() >= 0.2) ||
        !(v["floor_friction"].get<double>() <= 2.0))
      throw Error(path, where + ".floor_friction: must be a number in 0.2..2");
    venue.floorFriction = v["floor_friction"];
    const nlohmann::json& b = v.contains("balls") ? v["balls"] : nlohmann::json();
    if (!b.is_array() || b.size() != 2) throw Error(path, where + ".balls: must be two [x, y] pairs (own half, opponent half)");
    for (int k = 0; k < 2; ++k) {
      if (!b[k].is_array() || b[k].size() != 2 || !b[k][0].is_number() || !b[k][1].is_number())
        throw Error(path, where + ".balls[" + std::to_string(k) + "]: must be [x, y] in m");
      venue.balls[k] = Eigen::Vector2d(b[k][0].get<double>(), b[k][1].get<double>());
    }
    checkBalls(field, venue.balls, path + ": " + where + ".balls");
    if (v.contains("look")) venue.look = parseVenueLook(v["look"], venue.name, path, where + ".look");
    venue.look.name = venue.name;
    venues.push_back(venue);
  }
  return venues;
}

const Venue& venueNamed(const std::vector<Venue>& venues, const std::string& name) {
  std::string names;
  for (const Venue& v : venues) {
    if (v.name == name) return v;
    names += (names.empty() ? "" : ", ") + v.name;
  }
  throw Error("--venue", "unknown venue \"" + name + "\" (config/venues.json has " + names + ", or random)");
}

}  // namespace nao::sim
