#include "sim/Lighting.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "robot/Error.h"

namespace nao::sim {

namespace {

using nlohmann::json;

const char* const kFlag = "--lighting";

std::string trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) return "";
  return s.substr(begin, s.find_last_not_of(" \t\r\n") - begin + 1);
}

std::vector<std::string> split(const std::string& s, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(s);
  while (std::getline(in, part, separator)) parts.push_back(trim(part));
  if (!s.empty() && s.back() == separator) parts.push_back("");
  return parts;
}

std::string fmt(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// One key=value onto `l`. Errors name `where` (the flag or the presets file) and `context`
// (e.g. "presets.dark: ").
void applyKey(Lighting& l, const std::string& key, const std::string& value, const std::string& where,
              const std::string& context) {
  auto number = [&](double lo, double hi, bool openLow) {
    const char* begin = value.c_str();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(begin, &end);
    if (value.empty() || end != begin + value.size() || errno == ERANGE || !std::isfinite(v))
      throw Error(where, context + key + ": '" + value + "' is not a number");
    if ((openLow ? v <= lo : v < lo) || v > hi)
      throw Error(where, context + key + ": must be in " + (openLow ? "(" : "[") + fmt(lo) + ", " + fmt(hi) +
                             "], got " + value);
    return v;
  };
  if (key == "intensity") {
    l.intensity = number(0, 10, true);
  } else if (key == "temperature") {
    l.temperature = number(1000, 40000, false);
  } else if (key == "elevation") {
    l.elevation = number(0, 90, true);
  } else if (key == "azimuth") {
    l.azimuth = number(-360, 360, false);
  } else if (key == "ambient") {
    l.ambient = number(0, 2, false);
  } else if (key == "noise") {
    l.noise = number(0, 50, false);
  } else if (bool* flag = key == "shadows"      ? &l.shadows
                          : key == "camera"     ? &l.camera.enabled
                          : key == "ae"         ? &l.camera.autoExposure
                          : key == "awb"        ? &l.camera.autoWhiteBalance
                          : key == "vignetting" ? &l.camera.vignetting
                          : key == "defocus"    ? &l.camera.defocus
                          : key == "motion"     ? &l.camera.motion
                                                : nullptr) {
    std::string v = value;
    std::transform(v.begin(), v.end(), v.begin(), [](unsigned char c) { return std::tolower(c); });
    if (v == "on" || v == "true" || v == "yes" || v == "1") {
      *flag = true;
    } else if (v == "off" || v == "false" || v == "no" || v == "0") {
      *flag = false;
    } else {
      throw Error(where, context + key + ": must be on or off, got '" + value + "'");
    }
  } else {
    throw Error(where, context + "unknown key '" + key +
                           "' (keys: intensity, temperature, shadows, elevation, azimuth, ambient, noise, camera, "
                           "ae, awb, vignetting, defocus, motion)");
  }
}

void applyList(Lighting& l, const std::vector<std::string>& items, const std::string& where,
               const std::string& context) {
  for (const std::string& item : items) {
    const auto eq = item.find('=');
    if (item.empty()) throw Error(where, context + "empty item in the key=value list");
    if (eq == std::string::npos) throw Error(where, context + "'" + item + "' is not key=value");
    applyKey(l, trim(item.substr(0, eq)), trim(item.substr(eq + 1)), where, context);
  }
}

struct PresetFile {
  std::string path;
  json root;

  explicit PresetFile(const std::string& file) : path(file) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) throw Error(file, "file not found");
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    if (!in) throw Error(file, "cannot read file");
    try {
      root = json::parse(text.str());
    } catch (const json::exception& e) {
      std::string reason = e.what();
      for (char& c : reason)
        if (c == '\n') c = ' ';
      throw Error(file, "invalid JSON: " + reason);
    }
    if (!root.is_object()) throw Error(file, "top level: must be an object");
    auto presets = root.find("presets");
    if (presets == root.end()) throw Error(file, "presets: missing");
    if (!presets->is_object()) throw Error(file, "presets: must be an object of name -> \"key=value,...\"");
  }

  std::vector<std::string> names() const {
    std::vector<std::string> n;
    for (const auto& [name, value] : root["presets"].items()) n.push_back(name);
    return n;
  }

  Lighting preset(const std::string& name, const std::string& where, const Lighting& base) const {
    const json& presets = root["presets"];
    auto it = presets.find(name);
    if (it == presets.end()) {
      std::string known;
      for (const std::string& n : names()) known += (known.empty() ? "" : ", ") + n;
      throw Error(where, "unknown preset '" + name + "' (" + path + " has: " + known + ")");
    }
    const std::string context = "presets." + name + ": ";
    if (!it->is_string()) throw Error(path, context + "must be a string \"key=value,...\"");
    Lighting l = base;
    l.name = name;
    const std::string text = trim(it->get<std::string>());
    if (!text.empty()) applyList(l, split(text, ','), path, context);
    return l;
  }
};

// The camera model's parameters: config/camera_sensor.json beside the presets file, else the
// built-in defaults (a presets file elsewhere, e.g. a test's).
Lighting withCamera(const std::string& presetsFile) {
  Lighting l;
  const std::filesystem::path file = std::filesystem::path(presetsFile).parent_path() / "camera_sensor.json";
  std::error_code ec;
  if (std::filesystem::is_regular_file(file, ec)) l.camera = CameraSensorParams::load(file.string());
  return l;
}

}  // namespace

Eigen::Vector3d Lighting::colour() const {
  // Tanner Helland's fit of the black-body (Planckian locus) colour, 1000 K .. 40000 K.
  const double t = std::clamp(temperature, 1000.0, 40000.0) / 100.0;
  double r, g, b;
  if (t <= 66) {
    r = 255;
    g = 99.4708025861 * std::log(t) - 161.1195681661;
  } else {
    r = 329.698727446 * std::pow(t - 60, -0.1332047592);
    g = 288.1221695283 * std::pow(t - 60, -0.0755148492);
  }
  if (t >= 66) {
    b = 255;
  } else if (t <= 19) {
    b = 0;
  } else {
    b = 138.5177312231 * std::log(t - 10) - 305.0447927307;
  }
  Eigen::Vector3d c(std::clamp(r, 0.0, 255.0), std::clamp(g, 0.0, 255.0), std::clamp(b, 0.0, 255.0));
  return c / c.maxCoeff();
}

Lighting Lighting::parse(const std::string& spec, const std::string& presetsFile) {
  const std::string text = trim(spec);
  if (text.empty()) throw Error(kFlag, "empty lighting (give a preset name or key=value,...)");
  if (text == "sweep" || text.rfind("sweep,", 0) == 0)
    throw Error(kFlag, "'sweep' names several presets; only evaluations take it");
  std::vector<std::string> items = split(text, ',');
  Lighting l = withCamera(presetsFile);
  // An optional preset name first, then key=value overrides.
  if (!items.empty() && items.front().find('=') == std::string::npos && !items.front().empty()) {
    l = PresetFile(presetsFile).preset(items.front(), kFlag, l);
    items.erase(items.begin());
    if (items.empty()) return l;
  }
  applyList(l, items, kFlag, "");
  l.name = text;
  return l;
}

std::vector<Lighting> Lighting::sweep(const std::string& presetsFile, const std::string& overrides) {
  const PresetFile file(presetsFile);
  auto it = file.root.find("sweep");
  if (it == file.root.end()) throw Error(presetsFile, "sweep: missing");
  if (!it->is_array() || it->empty()) throw Error(presetsFile, "sweep: must be a non-empty list of preset names");
  std::vector<Lighting> result;
  const Lighting base = withCamera(presetsFile);
  const std::string extra = trim(overrides);
  for (const json& entry : *it) {
    if (!entry.is_string()) throw Error(presetsFile, "sweep: entries must be preset names");
    result.push_back(file.preset(entry.get<std::string>(), presetsFile, base));
    if (!extra.empty()) {
      applyList(result.back(), split(extra, ','), kFlag, "");
      result.back().name.append(1, ',').append(extra);
    }
  }
  return result;
}

}  // namespace nao::sim
