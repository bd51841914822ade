#include "robot/ModuleRegistry.h"

#include <set>
#include <stdexcept>

#include "robot/Error.h"
#include "robot/Text.h"

namespace nao {

namespace {

struct Entry {
  ModuleInfo info;
  std::vector<RepresentationType> required, provided;
  ModuleFactory factory;
};

// A function-local static: modules register during static initialisation, in any order.
std::map<std::string, Entry>& registry() {
  static std::map<std::string, Entry> r;
  return r;
}

const Entry* find(const std::string& name) {
  auto it = registry().find(name);
  return it == registry().end() ? nullptr : &it->second;
}

// Representation name -> the registered modules that can provide it.
std::map<std::string, std::vector<std::string>> possibleProviders() {
  std::map<std::string, std::vector<std::string>> r;
  for (const auto& [name, e] : registry())
    for (const auto& t : e.provided) r[t.name].push_back(name);
  return r;
}

void checkEntry(const std::string& rep, const std::string& module, const std::string& where) {
  const std::string key = escapeControl("providers." + rep);
  const auto possible = possibleProviders();
  if (!possible.count(rep)) throw Error(where, key + ": unknown representation (no registered module provides it)");
  const Entry* e = find(module);
  if (!e) throw Error(where, key + ": unknown module \"" + escapeControl(module) + "\"");
  for (const auto& t : e->provided)
    if (t.name == rep) return;
  throw Error(where, key + ": module " + module + " does not provide " + rep);
}

// A chosen module runs with all its provisions: each must be mapped to it.
void checkComplete(const ProviderMap& providers, const std::string& where) {
  for (const std::string& module : chosenModules(providers))
    for (const auto& t : find(module)->provided) {
      auto it = providers.find(t.name);
      if (it == providers.end())
        throw Error(where, "providers." + t.name + ": missing (" + module + ", chosen for another representation, provides it)");
      if (it->second != module)
        throw Error(where, "providers." + t.name + ": " + it->second + ", but " + module +
                               " (chosen for another representation) provides it too");
    }
}

}  // namespace

bool registerModule(ModuleInfo info, std::vector<RepresentationType> required, std::vector<RepresentationType> provided,
                    ModuleFactory factory) {
  for (const auto& t : required) info.required.push_back(t.name);
  for (const auto& t : provided) info.provided.push_back(t.name);
  const std::string name = info.name;
  if (!registry().emplace(name, Entry{std::move(info), std::move(required), std::move(provided), std::move(factory)}).second)
    throw std::logic_error("module " + name + " is registered twice");
  return true;
}

std::vector<ModuleInfo> registeredModules() {
  std::vector<ModuleInfo> r;
  for (const auto& [name, e] : registry()) r.push_back(e.info);
  return r;
}

std::unique_ptr<ModuleBase> createModule(const std::string& name, const ModuleContext& context) {
  const Entry* e = find(name);
  if (!e) throw Error("module " + name, "not registered (controllers/modules/" + name + ".cpp?)");
  std::unique_ptr<ModuleBase> m = e->factory(context);
  m->attachDebug(context.debug);
  return m;
}

void writeModuleGraphDot(std::ostream& out, const std::vector<ModuleInfo>& modules, const ProviderMap& providers) {
  const std::vector<std::string> chosenList = chosenModules(providers);
  const std::set<std::string> chosen(chosenList.begin(), chosenList.end());
  std::set<std::string> provided;
  std::vector<const ModuleInfo*> shown;
  for (const auto& m : modules) {
    if (!providers.empty() && !chosen.count(m.name)) continue;
    shown.push_back(&m);
    for (const auto& p : m.provided) provided.insert(p);
  }
  out << "digraph modules {\n  rankdir=LR;\n  node [fontname=\"Helvetica\", fontsize=10];\n";
  for (Cadence c : {Cadence::Motion, Cadence::Cognition}) {
    out << "  subgraph cluster_" << cadenceName(c) << " {\n    label=\"" << cadenceName(c) << "\";\n";
    for (const ModuleInfo* m : shown)
      if (m->cadence == c) out << "    \"" << m->name << "\" [shape=box];\n";
    out << "  }\n";
  }
  std::set<std::string> inputs;
  for (const ModuleInfo* m : shown)
    for (const auto& r : m->required)
      if (!provided.count(r)) inputs.insert(r);
  for (const auto& r : inputs) out << "  \"input:" << r << "\" [label=\"" << r << "\", shape=ellipse];\n";
  for (const ModuleInfo* consumer : shown)
    for (const auto& r : consumer->required) {
      if (inputs.count(r)) {
        out << "  \"input:" << r << "\" -> \"" << consumer->name << "\";\n";
        continue;
      }
      for (const ModuleInfo* producer : shown)
        for (const auto& p : producer->provided)
          if (p == r) out << "  \"" << producer->name << "\" -> \"" << consumer->name << "\" [label=\"" << r << "\"];\n";
    }
  out << "}\n";
}

namespace {

ProviderMap providersFromJson(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) throw Error(where, "must be a JSON object with \"providers\"");
  for (auto it = j.begin(); it != j.end(); ++it)
    if (it.key() != "providers" && it.key() != "comment") throw Error(where, escapeControl(it.key()) + ": unknown key");
  auto p = j.find("providers");
  if (p == j.end()) throw Error(where, "providers: missing");
  if (!p->is_object()) throw Error(where, "providers: must be an object (representation -> module)");
  ProviderMap providers;
  for (auto it = p->begin(); it != p->end(); ++it) {
    if (!it.value().is_string()) throw Error(where, escapeControl("providers." + it.key()) + ": must be a module name (a string)");
    checkEntry(it.key(), it.value().get<std::string>(), where);
    providers[it.key()] = it.value().get<std::string>();
  }
  checkComplete(providers, where);
  return providers;
}

}  // namespace

ProviderMap parseProviders(const std::string& text, const std::string& where) {
  return providersFromJson(parseJson(text, where), where);
}

ProviderMap loadProviders(const std::string& path) {
  const auto j = readJsonFile(path);
  if (!j) throw Error(path, "missing (it names each representation's provider)");
  return providersFromJson(*j, path);
}

void overrideProviders(ProviderMap& providers, const ProviderMap& overrides, const std::string& where) {
  for (const auto& [rep, module] : overrides) {
    if (module.empty()) {  // nobody: the representation becomes an input the caller writes
      if (!providers.erase(rep)) throw Error(where, "providers." + rep + ": has no provider to remove");
      continue;
    }
    checkEntry(rep, module, where);
    providers[rep] = module;
  }
  checkComplete(providers, where);
}

std::vector<std::string> chosenModules(const ProviderMap& providers) {
  std::set<std::string> names;
  for (const auto& [rep, module] : providers) names.insert(module);
  return {names.begin(), names.end()};
}

}  // namespace nao
