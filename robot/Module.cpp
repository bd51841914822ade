#include "robot/Module.h"

#include <map>
#include <set>
#include <stdexcept>

namespace nao {

void Pipeline::sort() {
  std::map<std::type_index, std::size_t> provider;
  for (std::size_t i = 0; i < modules_.size(); ++i)
    for (const auto& t : modules_[i]->provided()) {
      if (provider.count(t))
        throw std::logic_error("pipeline: " + std::string(t.name()) + " provided by both " +
                               modules_[provider[t]]->name() + " and " + modules_[i]->name());
      provider[t] = i;
    }
  const std::set<std::type_index> inputs(inputs_.begin(), inputs_.end());
  std::vector<std::unique_ptr<Module>> ordered;
  std::vector<int> state(modules_.size(), 0);  // 0 new, 1 visiting, 2 done
  auto visit = [&](auto&& self, std::size_t i) -> void {
    if (state[i] == 2) return;
    if (state[i] == 1) throw std::logic_error("pipeline: dependency cycle through " + modules_[i]->name());
    state[i] = 1;
    for (const auto& t : modules_[i]->required()) {
      if (inputs.count(t)) continue;
      auto it = provider.find(t);
      if (it == provider.end())
        throw std::logic_error("pipeline: " + modules_[i]->name() + " requires " + t.name() + ", which nothing provides");
      self(self, it->second);
    }
    state[i] = 2;
    ordered.push_back(std::move(modules_[i]));
  };
  for (std::size_t i = 0; i < modules_.size(); ++i)
    if (state[i] == 0) visit(visit, i);
  modules_ = std::move(ordered);
  sorted_ = true;
}

void Pipeline::update(Blackboard& blackboard) {
  if (!sorted_) sort();
  for (auto& m : modules_) m->update(blackboard);
}

std::vector<std::string> Pipeline::order() const {
  std::vector<std::string> names;
  for (const auto& m : modules_) names.push_back(m->name());
  return names;
}

}  // namespace nao
