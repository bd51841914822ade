#include "sim/VenueLook.h"

#include <cstdio>
#include <set>

#include <nlohmann/json.hpp>

#include "robot/Error.h"
#include "robot/Parameters.h"

namespace nao::sim {

namespace {

std::string shortNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

double number(const nlohmann::json& j, const char* key, double lo, double hi, double fallback, const std::string& path,
              const std::string& where) {
  if (!j.contains(key)) return fallback;
  const nlohmann::json& v = j[key];
  if (!v.is_number() || !(v.get<double>() >= lo) || !(v.get<double>() <= hi))
    throw Error(path, where + "." + key + ": must be a number in " + shortNumber(lo) + ".." + shortNumber(hi));
  return v.get<double>();
}

int count(const nlohmann::json& j, const char* key, int hi, int fallback, const std::string& path, const std::string& where) {
  if (!j.contains(key)) return fallback;
  const nlohmann::json& v = j[key];
  if (!v.is_number_integer() || v.get<long long>() < 0 || v.get<long long>() > hi)
    throw Error(path, where + "." + key + ": must be a whole number in 0.." + std::to_string(hi));
  return v.get<int>();
}

Eigen::Vector3d colour(const nlohmann::json& j, const char* key, const Eigen::Vector3d& fallback, const std::string& path,
                       const std::string& where) {
  if (!j.contains(key)) return fallback;
  const nlohmann::json& v = j[key];
  const std::string what = where + "." + key + ": must be [r, g, b], each in 0..1";
  if (!v.is_array() || v.size() != 3) throw Error(path, what);
  Eigen::Vector3d c;
  for (int k = 0; k < 3; ++k) {
    if (!v[k].is_number() || !(v[k].get<double>() >= 0) || !(v[k].get<double>() <= 1)) throw Error(path, what);
    c[k] = v[k].get<double>();
  }
  return c;
}

nlohmann::json rgb(const Eigen::Vector3d& c) { return {c.x(), c.y(), c.z()}; }

}  // namespace

VenueLook parseVenueLook(const nlohmann::json& j, const std::string& name, const std::string& path,
                         const std::string& where) {
  if (!j.is_object()) throw Error(path, where + ": must be an object");
  static const std::set<std::string> keys = {
      "turf",       "turf_patches", "turf_hue", "grain", "stripe_width", "stripe_contrast", "sheen",  "line_width_jitter",
      "line_bend",  "line_wear",    "wall",     "floor", "windows",      "doors",           "boards", "tables",
      "people",     "floor_lines"};
  for (const auto& [key, value] : j.items())
    if (!keys.count(key)) throw Error(path, where + "." + key + ": unknown key");
  VenueLook v;
  v.name = name;
  v.diagram = false;
  v.turf = colour(j, "turf", v.turf, path, where);
  if (!(v.turf.y() > v.turf.x() && v.turf.y() > v.turf.z()))
    throw Error(path, where + ".turf: the carpet must be green (g above r and b)");
  v.turfPatches = number(j, "turf_patches", 0, 0.2, v.turfPatches, path, where);
  v.turfHue = number(j, "turf_hue", 0, 0.1, v.turfHue, path, where);
  v.grain = number(j, "grain", 0, 0.4, v.grain, path, where);
  v.stripeWidth = number(j, "stripe_width", 0, 5, v.stripeWidth, path, where);
  v.stripeContrast = number(j, "stripe_contrast", 0, 0.15, v.stripeContrast, path, where);
  v.sheen = number(j, "sheen", 0, 0.5, v.sheen, path, where);
  v.lineWidthJitter = number(j, "line_width_jitter", 0, 0.2, v.lineWidthJitter, path, where);
  v.lineBend = number(j, "line_bend", 0, 0.02, v.lineBend, path, where);
  v.lineWear = number(j, "line_wear", 0, 0.3, v.lineWear, path, where);
  v.wall = colour(j, "wall", v.wall, path, where);
  v.floor = colour(j, "floor", v.floor, path, where);
  v.windows = count(j, "windows", 12, v.windows, path, where);
  v.doors = count(j, "doors", 8, v.doors, path, where);
  v.boards = count(j, "boards", 16, v.boards, path, where);
  v.tables = count(j, "tables", 8, v.tables, path, where);
  v.people = count(j, "people", 24, v.people, path, where);
  v.floorLines = colour(j, "floor_lines", v.floorLines, path, where);
  return v;
}

namespace {

const nlohmann::json& checkVenueFile(const nlohmann::json& j, const std::string& path) {
  if (!j.is_object() || !j.contains("venues") || !j["venues"].is_array() || j["venues"].empty())
    throw Error(path, "venues: must be a non-empty array");
  for (const auto& [key, value] : j.items())
    if (key != "venues" && key != "comment") throw Error(path, key + ": unknown key");
  std::set<std::string> names;
  for (std::size_t i = 0; i < j["venues"].size(); ++i) {
    const nlohmann::json& v = j["venues"][i];
    const std::string where = "venues[" + std::to_string(i) + "]";
    if (!v.is_object()) throw Error(path, where + ": must be an object");
    if (!v.contains("name") || !v["name"].is_string() || v["name"].get<std::string>().empty())
      throw Error(path, where + ".name: must be a non-empty string");
    const std::string name = v["name"];
    if (name == "none" || name == "random") throw Error(path, where + ".name: \"" + name + "\" is reserved");
    if (!names.insert(name).second) throw Error(path, where + ".name: \"" + name + "\" is there twice");
  }
  return j;
}

std::vector<VenueLook> looksOf(const nlohmann::json& j, const std::string& path) {
  std::vector<VenueLook> looks;
  for (std::size_t i = 0; i < j["venues"].size(); ++i) {
    const nlohmann::json& v = j["venues"][i];
    const std::string where = "venues[" + std::to_string(i) + "]";
    const std::string name = v["name"];
    if (v.contains("look")) {
      looks.push_back(parseVenueLook(v["look"], name, path, where + ".look"));
    } else {
      looks.emplace_back().name = name;
    }
  }
  return looks;
}

}  // namespace

nlohmann::json readVenueFile(const std::string& path) {
  const std::optional<nlohmann::json> file = readJsonFile(path);
  if (!file) throw Error(path, "cannot be read");
  return checkVenueFile(*file, path);
}

std::vector<VenueLook> loadVenueLooks(const std::string& path) { return looksOf(readVenueFile(path), path); }

std::vector<VenueLook> parseVenueLooks(const std::string& text, const std::string& path) {
  return looksOf(checkVenueFile(parseJson(text, path), path), path);
}

VenueLook venueLookFor(const std::vector<VenueLook>& looks, const std::string& venue, std::uint64_t seed) {
  if (venue == "none") return VenueLook{};
  if (venue == "random" && !looks.empty()) return looks[seed % looks.size()];
  std::string names;
  for (const VenueLook& v : looks) {
    if (v.name == venue) return v;
    names += (names.empty() ? "" : ", ") + v.name;
  }
  throw Error("--venue", "unknown venue \"" + venue + "\" (config/venues.json has " + names + "; or none, random)");
}

VenueChoice VenueChoice::load(const std::string& venue, const std::string& path) {
  VenueChoice c;
  c.venue = venue;
  if (venue != "none") {
    c.looks = loadVenueLooks(path);
    c.forSeed(0);  // an unknown name is refused now, not at the first trial
  }
  return c;
}

nlohmann::json toJson(const VenueLook& v) {
  if (v.plain()) return {{"name", v.name}, {"diagram", true}};
  return {{"name", v.name},
          {"turf", rgb(v.turf)},
          {"turf_patches", v.turfPatches},
          {"turf_hue", v.turfHue},
          {"grain", v.grain},
          {"stripe_width", v.stripeWidth},
          {"stripe_contrast", v.stripeContrast},
          {"sheen", v.sheen},
          {"line_width_jitter", v.lineWidthJitter},
          {"line_bend", v.lineBend},
          {"line_wear", v.lineWear},
          {"wall", rgb(v.wall)},
          {"floor", rgb(v.floor)},
          {"windows", v.windows},
          {"doors", v.doors},
          {"boards", v.boards},
          {"tables", v.tables},
          {"people", v.people},
          {"floor_lines", rgb(v.floorLines)}};
}

}  // namespace nao::sim
