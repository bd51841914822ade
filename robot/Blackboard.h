#pragma once
// The robot program's blackboard: one instance of each typed representation, written by the
// one module that provides it and read by the modules that require it. Modules never see the
// board itself: Module<Requires<...>, Provides<...>> (robot/Module.h) hands each module const
// references to what it requires and mutable ones to what it provides. The program, the
// backend glue and scenarios use the board directly for the pipeline's inputs.
// Representations are plain structs; any default-constructible type works.
#include <any>
#include <stdexcept>
#include <string>
#include <typeindex>
#include <typeinfo>
#include <unordered_map>

#include "robot/TypeName.h"

namespace nao {

class Blackboard {
 public:
  // The slot's address stays the same for the board's life (modules keep pointers to it).
  template <class T>
  T& write() {
    auto [it, inserted] = slots_.try_emplace(std::type_index(typeid(T)));
    if (inserted) it->second.emplace<T>();
    return *std::any_cast<T>(&it->second);
  }
  template <class T>
  const T& read() const {
    auto it = slots_.find(std::type_index(typeid(T)));
    if (it == slots_.end()) throw std::logic_error("blackboard: nothing provides " + typeName<T>());
    return *std::any_cast<T>(&it->second);
  }
  template <class T>
  bool has() const {
    return has(std::type_index(typeid(T)));
  }
  bool has(std::type_index type) const { return slots_.count(type) != 0; }

 private:
  std::unordered_map<std::type_index, std::any> slots_;
};

}  // namespace nao
