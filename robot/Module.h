#pragma once
// A module of the robot program: it declares the representations it requires and provides,
// and computes its provisions once per cycle in update(). The Pipeline orders modules so that
// every requirement is provided before it is read.
#include <memory>
#include <string>
#include <typeindex>
#include <vector>

#include "robot/Blackboard.h"

namespace nao {

class Module {
 public:
  virtual ~Module() = default;
  virtual std::string name() const = 0;
  virtual void update(Blackboard& blackboard) = 0;

  const std::vector<std::type_index>& required() const { return requires_; }
  const std::vector<std::type_index>& provided() const { return provides_; }

 protected:
  template <class... T>
  void require() { (requires_.emplace_back(typeid(T)), ...); }
  template <class... T>
  void provide() { (provides_.emplace_back(typeid(T)), ...); }

 private:
  std::vector<std::type_index> requires_, provides_;
};

// Runs modules in dependency order. Representations written by the backend (sensor data,
// images) are declared as inputs.
class Pipeline {
 public:
  void add(std::unique_ptr<Module> module) { modules_.push_back(std::move(module)); sorted_ = false; }
  template <class... T>
  void inputs() { (inputs_.emplace_back(typeid(T)), ...); sorted_ = false; }
  // Orders the modules; throws std::logic_error naming a module whose requirement nobody
  // provides, a representation with two providers, or a cycle.
  void sort();
  void update(Blackboard& blackboard);
  std::vector<std::string> order() const;

 private:
  std::vector<std::unique_ptr<Module>> modules_;
  std::vector<std::type_index> inputs_;
  bool sorted_ = false;
};

}  // namespace nao
