#include "robot/Parameters.h"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "robot/Text.h"

namespace nao {

namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// nlohmann's messages start with "[json.exception.parse_error.101] "; the rest is one line.
std::string withoutTag(const std::string& what) {
  const std::size_t p = what.find("] ");
  return p != std::string::npos && what.rfind("[json.exception", 0) == 0 ? what.substr(p + 2) : what;
}

}  // namespace

ParamReader::ParamReader(const nlohmann::json& object, std::string file, std::string prefix)
    : object_(object), file_(std::move(file)), prefix_(std::move(prefix)) {}

const nlohmann::json* ParamReader::take(const char* key) {
  seen_.insert(key);
  auto it = object_.find(key);
  return it == object_.end() ? nullptr : &*it;
}

void ParamReader::fail(const std::string& key, const std::string& what) const {
  throw Error(file_, escapeControl(prefix_ + key + ": " + what));
}

void ParamReader::operator()(const char* key, double& value, double min, double max) {
  const nlohmann::json* j = take(key);
  if (!j) return;
  if (!j->is_number()) fail(key, "must be a number");
  const double v = j->get<double>();
  // JSON text has no NaN and the parser refuses 1e999, but a JSON value built in code may hold either.
  if (!std::isfinite(v)) fail(key, "must be finite");
  if (v < min || v > max) fail(key, number(v) + " is out of range [" + number(min) + ", " + number(max) + "]");
  value = v;
}

void ParamReader::operator()(const char* key, int& value, int min, int max) {
  const nlohmann::json* j = take(key);
  if (!j) return;
  if (!j->is_number_integer()) fail(key, "must be an integer");
  bool inRange;
  if (j->is_number_unsigned()) {
    const std::uint64_t u = j->get<std::uint64_t>();
    inRange = max >= 0 && u <= static_cast<std::uint64_t>(max) && static_cast<std::int64_t>(u) >= min;
  } else {
    const std::int64_t v = j->get<std::int64_t>();
    inRange = v >= min && v <= max;
  }
  if (!inRange) fail(key, j->dump() + " is out of range [" + std::to_string(min) + ", " + std::to_string(max) + "]");
  value = static_cast<int>(j->get<std::int64_t>());
}

void ParamReader::operator()(const char* key, bool& value) {
  const nlohmann::json* j = take(key);
  if (!j) return;
  if (!j->is_boolean()) fail(key, "must be true or false");
  value = j->get<bool>();
}

void ParamReader::operator()(const char* key, std::string& value, std::initializer_list<const char*> choices) {
  const nlohmann::json* j = take(key);
  if (!j) return;
  std::string list;
  for (const char* c : choices) list += (list.empty() ? "" : ", ") + std::string(c);
  if (!j->is_string()) fail(key, "must be one of " + list);
  const std::string v = j->get<std::string>();
  for (const char* c : choices)
    if (v == c) {
      value = v;
      return;
    }
  fail(key, "must be one of " + list + ", not '" + escapeControl(v).substr(0, 40) + "'");
}

void ParamReader::operator()(const char* key, std::string& value) {
  const nlohmann::json* j = take(key);
  if (!j) return;
  if (!j->is_string()) fail(key, "must be a string");
  const std::string v = j->get<std::string>();
  if (v.size() > 2000) fail(key, "is longer than 2000 characters");
  value = v;
}

void ParamReader::operator()(const char* key, std::vector<double>& values, double min, double max) {
  const nlohmann::json* j = take(key);
  if (!j) return;
  if (!j->is_array() || j->empty() || j->size() > 64) fail(key, "must be a list of 1 to 64 numbers");
  std::vector<double> out;
  for (std::size_t i = 0; i < j->size(); ++i) {
    const nlohmann::json& e = (*j)[i];
    const std::string at = std::string(key) + "[" + std::to_string(i) + "]";
    if (!e.is_number()) fail(at, "must be a number");
    const double v = e.get<double>();
    if (!std::isfinite(v)) fail(at, "must be finite");
    if (v < min || v > max) fail(at, number(v) + " is out of range [" + number(min) + ", " + number(max) + "]");
    out.push_back(v);
  }
  values = std::move(out);
}

void ParamReader::finish() const {
  for (auto it = object_.begin(); it != object_.end(); ++it)
    if (!seen_.count(it.key())) fail(it.key(), "unknown parameter");
}

nlohmann::json parseJson(const std::string& text, const std::string& where) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw Error(where, "not valid JSON: " + escapeControl(withoutTag(e.what())));
  }
}

std::optional<nlohmann::json> readJsonFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (std::FILE* f = std::fopen(path.c_str(), "rb")) {  // exists but unreadable
      std::fclose(f);
      throw Error(path, "cannot be read");
    }
    return std::nullopt;
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error(path, "cannot be read");
  return parseJson(text.str(), path);
}

std::string parameterFile(const std::string& configDir, const std::string& module) {
  return configDir + "/parameters/" + module + ".json";
}

std::string robotParameterFile(const std::string& configDir, const std::string& headId, const std::string& module) {
  // The head id becomes a folder name: nothing that could leave config/robots/.
  for (char c : headId)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'))
      throw Error("head id", "\"" + headId + "\" may hold only letters, digits, '-' and '_'");
  return configDir + "/robots/" + headId + "/" + module + ".json";
}

}  // namespace nao
