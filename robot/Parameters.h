#pragma once
// Module parameters from files: config/parameters/<module>.json, then the per-robot overlay
// config/robots/<head id>/<module>.json. A missing file keeps the defaults (the Params struct's
// initialisers); keys a file leaves out keep theirs too. An unknown key, a wrong type, a
// number that is not finite or out of its range is a nao::Error naming the file and the key
// ("config/parameters/HeadControl.json: maxYawSpeed: 40 is out of range [0, 10]").
//
// A Params struct lists its fields once, with their ranges, in a free function found by ADL:
//
//   template <class V> void describe(V& v, HeadControl::Params& p) {
//     v("maxYawSpeed", p.maxYawSpeed, 0.0, 10.0);   // double: min, max
//     v("gyroOdometry", p.gyroOdometry);            // bool
//     v("walk", p.walk);                            // a nested Params: a JSON object
//   }
//
// The same list reads (ParamReader) and writes (ParamWriter) the file, so the committed files
// can be checked against the defaults.
#include <any>
#include <cstdint>
#include <map>
#include <initializer_list>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "robot/Error.h"
#include "robot/TypeName.h"

namespace nao {

class DebugChannels;  // robot/Debug.h

class ParamReader {
 public:
  // object: the JSON object for this struct; file: named in errors; prefix: "walk." for nested ones.
  ParamReader(const nlohmann::json& object, std::string file, std::string prefix = "");

  void operator()(const char* key, double& value, double min, double max);
  void operator()(const char* key, int& value, int min, int max);
  void operator()(const char* key, bool& value);
  // A word from a fixed set (a solver's name, a source).
  void operator()(const char* key, std::string& value, std::initializer_list<const char*> choices);
  // Free text (a note such as the command that fitted the figures): at most 2000 characters.
  void operator()(const char* key, std::string& value);
  // A list of 1 to 64 numbers, each in [min, max] (a table over distance bins).
  void operator()(const char* key, std::vector<double>& values, double min, double max);
  template <class S>
  void operator()(const char* key, S& nested) {
    const nlohmann::json* j = take(key);
    if (!j) return;
    if (!j->is_object()) fail(key, "must be an object");
    ParamReader inner(*j, file_, prefix_ + key + ".");
    describe(inner, nested);
    inner.finish();
  }
  // Throws for a key that describe() did not name.
  void finish() const;

 private:
  const nlohmann::json* take(const char* key);
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

  const nlohmann::json& object_;
  std::string file_, prefix_;
  std::set<std::string> seen_;
};

class ParamWriter {
 public:
  void operator()(const char* key, double& value, double, double) { json_[key] = value; }
  void operator()(const char* key, int& value, int, int) { json_[key] = value; }
  void operator()(const char* key, bool& value) { json_[key] = value; }
  void operator()(const char* key, std::string& value, std::initializer_list<const char*>) { json_[key] = value; }
  void operator()(const char* key, std::string& value) { json_[key] = value; }
  void operator()(const char* key, std::vector<double>& values, double, double) { json_[key] = values; }
  template <class S>
  void operator()(const char* key, S& nested) {
    ParamWriter inner;
    describe(inner, nested);
    json_[key] = inner.json();
  }
  // In describe()'s order, as the files are written.
  const nlohmann::ordered_json& json() const { return json_; }

 private:
  nlohmann::ordered_json json_ = nlohmann::ordered_json::object();
};

// JSON text -> value; a syntax error is one line: "<where>: not valid JSON: ... at line 3, column 7".
nlohmann::json parseJson(const std::string& text, const std::string& where);
// The file's JSON; nothing when the file does not exist. Unreadable or invalid: nao::Error.
std::optional<nlohmann::json> readJsonFile(const std::string& path);

// Applies the keys of a JSON object onto p (keys left out keep p's values).
template <class P>
void applyParams(const nlohmann::json& object, const std::string& file, P& p) {
  if (!object.is_object()) throw Error(file, "must be a JSON object of parameters");
  ParamReader reader(object, file);
  describe(reader, p);
  reader.finish();
}
template <class P>
void applyParamsText(const std::string& text, const std::string& file, P& p) {
  applyParams(parseJson(text, file), file, p);
}
template <class P>
nlohmann::ordered_json paramsToJson(P p) {
  ParamWriter writer;
  describe(writer, p);
  return writer.json();
}

// The files a module's parameters come from, in the order they apply.
std::string parameterFile(const std::string& configDir, const std::string& module);
std::string robotParameterFile(const std::string& configDir, const std::string& headId, const std::string& module);

template <class P>
P loadParams(const std::string& module, const std::string& configDir, const std::string& headId = "") {
  P p{};
  const std::string base = parameterFile(configDir, module);
  if (const auto j = readJsonFile(base)) applyParams(*j, base, p);
  if (!headId.empty()) {
    const std::string overlay = robotParameterFile(configDir, headId, module);
    if (const auto j = readJsonFile(overlay)) applyParams(*j, overlay, p);
  }
  return p;
}

// What a module's constructor gets: where its parameters come from.
struct ModuleContext {
  std::string configDir;  // holds parameters/ and robots/; empty: every module keeps its defaults
  std::string headId;     // the robot's head id (per-robot overlay); empty: none
  // Module name -> its Params, used instead of the files (a scenario's trial parameters, tests).
  std::map<std::string, std::any> params;
  // The program's debug channels (not owned; null: none): createModule attaches them to the
  // module, and a module that owns helpers or pipelines of its own hands them on.
  DebugChannels* debug = nullptr;
  // Seeds the random draws of a module that makes any (the fast percept mode's OracleVision):
  // the run's seed, so that the same seed gives the same run and another seed another one.
  std::uint64_t seed = 0;

  template <class P>
  P load(const std::string& module) const {
    if (auto it = params.find(module); it != params.end()) {
      if (const P* p = std::any_cast<P>(&it->second)) return *p;
      throw Error("ModuleContext.params", module + ": holds no " + typeName<P>());
    }
    return configDir.empty() ? P{} : loadParams<P>(module, configDir, headId);
  }
};

}  // namespace nao
