#pragma once
// Every module of the robot program registers itself by name (NAO_REGISTER_MODULE at the end of
// its .cpp), with a factory and its declarations. config/modules.json says which module
// provides which representation; the robot program builds its pipeline from that, so a
// scenario can swap one provider (e.g. an oracle from the simulator's truth).
//
// The module files live in controllers/modules/; controllers/CMakeLists.txt makes every
// program that links nao_controllers keep them (a static library would drop objects nothing
// refers to), by the file name: controllers/modules/<Name>.cpp must register <Name>.
#include <functional>
#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao {

struct ModuleInfo {
  std::string name;
  Cadence cadence = Cadence::Motion;
  std::vector<std::string> required, provided;  // representation names, as declared
};

using ModuleFactory = std::function<std::unique_ptr<ModuleBase>(const ModuleContext&)>;

// Called by NAO_REGISTER_MODULE; a name registered twice throws (at start-up).
bool registerModule(ModuleInfo info, std::vector<RepresentationType> required,
                    std::vector<RepresentationType> provided, ModuleFactory factory);

// Every registered module, by name: what `nao-soccer modules` lists.
std::vector<ModuleInfo> registeredModules();
// Throws nao::Error for a name nobody registered.
std::unique_ptr<ModuleBase> createModule(const std::string& name, const ModuleContext& context = {});

// Graphviz: a box per module (grouped by cadence), an edge per representation from its
// provider to each module that requires it; representations no module provides (the
// pipeline's inputs) appear as ellipses. providers (representation -> module) marks the
// chosen provider where several modules could provide one; empty: every module is drawn.
void writeModuleGraphDot(std::ostream& out, const std::vector<ModuleInfo>& modules,
                         const std::map<std::string, std::string>& providers = {});

// config/modules.json: {"providers": {"<Representation>": "<Module>", ...}}.
// Representation -> module, checked against the registry: malformed JSON, an unknown
// representation or module, a module that does not provide the representation, a chosen
// module whose other provisions are mapped elsewhere or not at all: nao::Error naming the file
// and the key ("config/modules.json: providers.FallState: unknown module \"FallDetektor\"").
using ProviderMap = std::map<std::string, std::string>;
ProviderMap loadProviders(const std::string& path);
ProviderMap parseProviders(const std::string& text, const std::string& where);
// Replaces entries of `providers` (e.g. a scenario's oracle) and checks the result again;
// errors name `where` and the key. An empty module name removes the entry: nobody provides the
// representation (a scenario that drives the robot writes it).
void overrideProviders(ProviderMap& providers, const ProviderMap& overrides, const std::string& where);
// The modules a provider map chooses, by name, each once.
std::vector<std::string> chosenModules(const ProviderMap& providers);

}  // namespace nao

// At namespace scope in the module's .cpp, after its class: NAO_REGISTER_MODULE(FallDetector).
// The module needs a constructor taking const ModuleContext& (its parameters come from there).
#define NAO_REGISTER_MODULE(Type)                                                                          \
  extern "C" void nao_module_##Type() {}                                                                   \
  [[maybe_unused]] static const bool naoModuleRegistered_##Type = ::nao::registerModule(                   \
      ::nao::ModuleInfo{::nao::shortTypeName<Type>(), Type::kCadence, {}, {}}, Type::declaredRequires(),  \
      Type::declaredProvides(),                                                                            \
      [](const ::nao::ModuleContext& context) -> std::unique_ptr<::nao::ModuleBase> {                      \
        return std::make_unique<Type>(context);                                                            \
      })
