#pragma once
// The robot program's blackboard: one instance of each typed representation, written by the
// one module that provides it and read by the modules that require it (B-Human's
// REQUIRES/PROVIDES). Representations are plain structs; any default-constructible type works.
#include <any>
#include <stdexcept>
#include <string>
#include <typeindex>
#include <typeinfo>
#include <unordered_map>

namespace nao {

class Blackboard {
 public:
  template <class T>
  T& write() {
    auto [it, inserted] = slots_.try_emplace(std::type_index(typeid(T)));
    if (inserted) it->second.emplace<T>();
    return *std::any_cast<T>(&it->second);
  }
  template <class T>
  const T& read() const {
    auto it = slots_.find(std::type_index(typeid(T)));
    if (it == slots_.end()) throw std::logic_error(std::string("blackboard: nothing provides ") + typeid(T).name());
    return *std::any_cast<T>(&it->second);
  }
  template <class T>
  bool has() const {
    return slots_.count(std::type_index(typeid(T))) != 0;
  }

 private:
  std::unordered_map<std::type_index, std::any> slots_;
};

}  // namespace nao
