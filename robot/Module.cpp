#include "robot/Module.h"

#include <algorithm>
#include <chrono>
#include <map>

#include "robot/Error.h"

namespace nao {

NAO_DEBUG_CHANNEL(kTiming, "timing",
                  "every pipeline run: each module's update in ms (steady clock) with its cadence; at a robot "
                  "program's end a summary per pipeline (runs, mean and maximum ms per module)");

void Pipeline::setDebug(DebugChannels* debug, std::string name) {
  debug_ = debug;
  name_ = std::move(name);
  for (auto& m : modules_) m->attachDebug(debug);
}

bool Pipeline::timing() const { return debug_ && debug_->on(kTiming); }

void Pipeline::writeTiming(const std::vector<double>& ms) {
  if (!timing()) return;
  sumMs_.resize(modules_.size());
  maxMs_.resize(modules_.size());
  ++timedRuns_;
  nlohmann::json modules = nlohmann::json::array();
  double total = 0;
  for (std::size_t i = 0; i < modules_.size() && i < ms.size(); ++i) {
    modules.push_back({{"module", modules_[i]->name()}, {"cadence", cadenceName(modules_[i]->cadence())}, {"ms", ms[i]}});
    total += ms[i];
    sumMs_[i] += ms[i];
    maxMs_[i] = std::max(maxMs_[i], ms[i]);
  }
  debug_->write(kTiming, {{"pipeline", name_}, {"modules", std::move(modules)}, {"total_ms", total}});
}

void Pipeline::writeTimingSummary() const {
  if (!timing()) return;
  nlohmann::json modules = nlohmann::json::array();
  for (std::size_t i = 0; i < modules_.size(); ++i) {
    const bool ran = timedRuns_ > 0 && i < sumMs_.size();
    modules.push_back({{"module", modules_[i]->name()},
                       {"cadence", cadenceName(modules_[i]->cadence())},
                       {"runs", ran ? timedRuns_ : 0},
                       {"ms_mean", ran ? sumMs_[i] / static_cast<double>(timedRuns_) : 0.0},
                       {"ms_max", ran ? maxMs_[i] : 0.0}});
  }
  debug_->write(kTiming, {{"pipeline", name_}, {"summary", true}, {"runs", timedRuns_}, {"modules", std::move(modules)}});
}

void Pipeline::sort() {
  const std::string where = "module pipeline";
  std::map<std::type_index, std::size_t> provider;
  std::map<std::type_index, std::string> inputs;
  for (const auto& t : inputs_) inputs.emplace(t.type, t.name);
  for (std::size_t i = 0; i < modules_.size(); ++i)
    for (const auto& t : modules_[i]->provided()) {
      if (inputs.count(t.type))
        throw Error(where, t.name + " is an input of the pipeline and provided by " + modules_[i]->name() + " too");
      if (auto it = provider.find(t.type); it != provider.end())
        throw Error(where, t.name + " is provided by both " + modules_[it->second]->name() + " and " + modules_[i]->name());
      provider[t.type] = i;
    }

  // Depth-first, in the order the modules were added, so the order is reproducible.
  std::vector<std::size_t> ordered;
  std::vector<int> state(modules_.size(), 0);  // 0 new, 1 on the path, 2 done
  std::vector<std::pair<std::size_t, std::string>> path;  // module, the representation it waits for
  auto visit = [&](auto&& self, std::size_t i) -> void {
    if (state[i] == 2) return;
    if (state[i] == 1) {
      std::string cycle;
      std::size_t k = 0;
      while (path[k].first != i) ++k;
      for (; k < path.size(); ++k)
        cycle += modules_[path[k].first]->name() + " requires " + path[k].second + " from ";
      throw Error(where, "dependency cycle: " + cycle + modules_[i]->name());
    }
    state[i] = 1;
    for (const auto& t : modules_[i]->required()) {
      if (inputs.count(t.type)) continue;
      auto it = provider.find(t.type);
      if (it == provider.end())
        throw Error(where, modules_[i]->name() + " requires " + t.name + ", which no module provides and no input is");
      if (t.previous) continue;  // the last run's value: no ordering edge
      path.emplace_back(i, t.name);
      self(self, it->second);
      path.pop_back();
    }
    state[i] = 2;
    ordered.push_back(i);
  };
  for (std::size_t i = 0; i < modules_.size(); ++i)
    if (state[i] == 0) visit(visit, i);
  // Only a complete order replaces the modules: a failed sort leaves them as they were.
  std::vector<std::unique_ptr<ModuleBase>> sorted;
  for (std::size_t i : ordered) sorted.push_back(std::move(modules_[i]));
  modules_ = std::move(sorted);
  sorted_ = true;
}

void Pipeline::update(Blackboard& blackboard) {
  if (!sorted_) sort();
  if (!timing()) {
    for (auto& m : modules_) m->execute(blackboard);
    return;
  }
  using Clock = std::chrono::steady_clock;
  std::vector<double> ms;
  ms.reserve(modules_.size());
  Clock::time_point last = Clock::now();
  for (auto& m : modules_) {
    m->execute(blackboard);
    const Clock::time_point now = Clock::now();
    ms.push_back(std::chrono::duration<double, std::milli>(now - last).count());
    last = now;
  }
  writeTiming(ms);
}

std::vector<std::string> Pipeline::order() const {
  std::vector<std::string> names;
  for (const auto& m : modules_) names.push_back(m->name());
  return names;
}

}  // namespace nao
