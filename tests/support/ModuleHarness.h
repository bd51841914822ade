#pragma once
// Runs one module alone: fix its inputs, run update, read its outputs. The module sees the
// same bindings as in the pipeline (its own blackboard here), so what it may read and write
// is checked exactly as in the robot program.
//
//   ModuleHarness h = ModuleHarness::make<modules::FallDetector>();   // or ModuleHarness("FallDetector")
//   h.fix(frame);            // a SensorFrame
//   h.run();
//   EXPECT_TRUE(h.get<FallState>().fallen);
#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "robot/Blackboard.h"
#include "robot/Module.h"
#include "robot/ModuleRegistry.h"
#include "robot/Parameters.h"

namespace nao::testing {

class ModuleHarness {
 public:
  // By registered name; context: where parameters come from (default: the compiled-in defaults).
  explicit ModuleHarness(const std::string& name, const ModuleContext& context = {})
      : module_(createModule(name, context)) {}
  explicit ModuleHarness(std::unique_ptr<ModuleBase> module) : module_(std::move(module)) {}
  // By type, with its parameters given directly (or loaded through the context).
  template <class M, class... Args>
  static ModuleHarness make(Args&&... args) {
    return ModuleHarness(std::make_unique<M>(std::forward<Args>(args)...));
  }

  // Sets a required representation (anything else is a mistake in the test: it throws).
  template <class T>
  ModuleHarness& fix(const T& value) {
    if (!declares(module_->required(), typeid(T)))
      throw std::logic_error(module_->name() + " does not require " + typeName<T>());
    board_.write<T>() = value;
    return *this;
  }
  // The input to change in place between runs.
  template <class T>
  T& input() {
    if (!declares(module_->required(), typeid(T)))
      throw std::logic_error(module_->name() + " does not require " + typeName<T>());
    return board_.write<T>();
  }
  // One update. Every requirement must have been fixed.
  ModuleHarness& run() {
    for (const auto& t : module_->required())
      if (!board_.has(t.type)) throw std::logic_error(module_->name() + " requires " + t.name + ", not fixed");
    module_->execute(board_);
    return *this;
  }
  template <class T>
  const T& get() const {
    if (!declares(module_->provided(), typeid(T)))
      throw std::logic_error(module_->name() + " does not provide " + typeName<T>());
    return board_.read<T>();
  }
  ModuleBase& module() { return *module_; }
  // The module as its type, e.g. to look at its state.
  template <class M>
  M& as() {
    M* m = dynamic_cast<M*>(module_.get());
    if (!m) throw std::logic_error("ModuleHarness::as: " + module_->name() + " is not a " + typeName<M>());
    return *m;
  }

 private:
  static bool declares(const std::vector<RepresentationType>& list, const std::type_info& type) {
    return std::any_of(list.begin(), list.end(), [&](const RepresentationType& t) { return t.type == type; });
  }

  std::unique_ptr<ModuleBase> module_;
  Blackboard board_;
};

}  // namespace nao::testing
