#include "perception/calibration/CalibrationStore.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "robot/Error.h"
#include "robot/OutputFiles.h"
#include "robot/Paths.h"

namespace nao::calibration {
namespace {

using json = nlohmann::json;
constexpr double kDeg = M_PI / 180;
constexpr double kMaxOffsetDeg = 20;  // beyond this it is not a miscalibration but a broken robot

const json& member(const json& obj, const std::string& key, const std::string& path, const std::string& source) {
  const auto it = obj.find(key);
  if (it == obj.end()) throw Error(source, path + ": missing");
  return *it;
}

double number(const json& obj, const std::string& key, const std::string& path, const std::string& source) {
  const json& v = member(obj, key, path, source);
  if (!v.is_number()) throw Error(source, path + ": must be a number (got " + v.type_name() + ")");
  const double d = v.get<double>();
  if (!std::isfinite(d)) throw Error(source, path + ": must be finite");
  return d;
}

}  // namespace

CalibrationStore::CalibrationStore(std::string dir) : dir_(dir.empty() ? dataPath("config/calibration") : std::move(dir)) {}

std::string CalibrationStore::pathFor(const std::string& headId) const {
  if (headId.empty() || headId.size() > 128 || headId[0] == '.')
    throw Error("head id", "'" + headId + "' is not usable as a file name");
  for (char c : headId)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.'))
      throw Error("head id", "'" + headId + "' may only hold letters, digits, '-', '_' and '.'");
  return dir_ + "/" + headId + ".json";
}

CalibrationRecord CalibrationStore::parse(const std::string& text, const std::string& source) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::exception& e) {
    throw Error(source, std::string("invalid JSON: ") + e.what());
  }
  if (!root.is_object()) throw Error(source, "top level: must be an object");
  CalibrationRecord r;
  const json& offsets = member(root, "offsets_deg", "offsets_deg", source);
  if (!offsets.is_object()) throw Error(source, "offsets_deg: must be an object");
  std::array<double, 6> a{};
  for (int k = 0; k < 6; ++k) {
    const std::string name = CameraCalibration::kNames[k];
    const double deg = number(offsets, name, "offsets_deg." + name, source);
    if (std::abs(deg) > kMaxOffsetDeg)
      throw Error(source, "offsets_deg." + name + ": " + std::to_string(deg) + " deg is beyond +-20 deg");
    a[k] = deg * kDeg;
  }
  r.offsets = CameraCalibration::fromArray(a);
  if (root.contains("rms_angle_deg")) r.rmsAngleDeg = number(root, "rms_angle_deg", "rms_angle_deg", source);
  if (root.contains("rms_depth_m")) r.rmsDepthM = number(root, "rms_depth_m", "rms_depth_m", source);
  if (root.contains("samples")) r.samples = static_cast<int>(number(root, "samples", "samples", source));
  if (root.contains("solver")) {
    if (!root["solver"].is_string()) throw Error(source, "solver: must be a string");
    r.solver = root["solver"].get<std::string>();
  }
  return r;
}

std::string CalibrationStore::serialize(const std::string& headId, const CalibrationRecord& r) {
  json offsets = json::object();
  const auto a = r.offsets.toArray();
  for (int k = 0; k < 6; ++k) offsets[CameraCalibration::kNames[k]] = a[k] / kDeg;
  const json j = {{"head_id", headId},          {"offsets_deg", offsets},  {"rms_angle_deg", r.rmsAngleDeg},
                  {"rms_depth_m", r.rmsDepthM}, {"samples", r.samples},    {"solver", r.solver}};
  return j.dump(2) + "\n";
}

std::optional<CalibrationRecord> CalibrationStore::load(const std::string& headId) const {
  const std::string path = pathFor(headId);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  CalibrationRecord r = parse(text.str(), path);
  const json root = json::parse(text.str());
  if (root.contains("head_id") && (!root["head_id"].is_string() || root["head_id"].get<std::string>() != headId))
    throw Error(path, "head_id: does not match the file name (" + headId + ")");
  return r;
}

CameraCalibration CalibrationStore::offsetsFor(const std::string& headId) const {
  const auto r = load(headId);
  return r ? r->offsets : CameraCalibration{};
}

SaveOutcome CalibrationStore::save(const std::string& headId, const CalibrationRecord& r) const {
  SaveOutcome out;
  out.path = pathFor(headId);
  char buf[160];
  for (double v : r.offsets.toArray())
    if (!std::isfinite(v) || std::abs(v) > kMaxOffsetDeg * kDeg) {
      out.reason = "refused: an offset is not finite or beyond +-20 deg";
      return out;
    }
  if (!r.converged) {
    out.reason = "refused: the solver did not converge";
    return out;
  }
  if (!(r.rmsAngleDeg <= maxRmsAngleDeg)) {
    std::snprintf(buf, sizeof buf, "refused: right-angle residuals %.3f deg RMS exceed %.3f deg", r.rmsAngleDeg,
                  maxRmsAngleDeg);
    out.reason = buf;
    return out;
  }
  if (!(r.rmsDepthM <= maxRmsDepthM)) {
    std::snprintf(buf, sizeof buf, "refused: goal-box depth residuals %.4f m RMS exceed %.4f m", r.rmsDepthM, maxRmsDepthM);
    out.reason = buf;
    return out;
  }
  io::makeDirectories(dir_);
  io::writeFile(out.path, serialize(headId, r));
  out.saved = true;
  return out;
}

}  // namespace nao::calibration
