#include "scenarios/EvalRows.h"

#include "robot/Error.h"

namespace nao::sim {

std::map<std::uint64_t, nlohmann::json> rowsBySeed(std::vector<nlohmann::json> rows, const nlohmann::json& settings) {
  std::map<std::uint64_t, nlohmann::json> done;
  for (auto& r : rows) {
    if (!r.is_object() || !r.contains("seed") || !r.contains("settings")) throw Error("--rows", "a row without seed or settings");
    if (r.at("settings") != settings)
      throw Error("--rows", "rows of other settings (" + r.at("settings").dump() + ", this run " + settings.dump() + ")");
    const auto seed = r.at("seed").get<std::uint64_t>();  // before the move: json's operator= takes its argument by value
    done[seed] = std::move(r);
  }
  return done;
}

}  // namespace nao::sim
