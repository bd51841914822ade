#include "scenarios/EvalRows.h"

#include "robot/Error.h"

namespace nao::sim {

std::vector<std::uint64_t> trialSeeds(std::uint64_t first, int count, const std::vector<std::uint64_t>& list,
                                      const char* countFlag) {
  if (!list.empty()) return list;
  if (count < 1) throw Error(countFlag, "must be at least 1");
  std::vector<std::uint64_t> seeds;
  for (int i = 0; i < count; ++i) seeds.push_back(first + static_cast<std::uint64_t>(i));
  return seeds;
}

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

std::vector<nlohmann::json> collectRows(const std::vector<std::uint64_t>& seeds, std::map<std::uint64_t, nlohmann::json> done,
                                        const std::function<nlohmann::json(std::uint64_t seed)>& run,
                                        const std::function<void(const nlohmann::json& row)>& onRow,
                                        const std::function<void(const nlohmann::json& row, int done, int total)>& progress,
                                        const std::function<void(const nlohmann::json& row)>& checkDone) {
  std::vector<nlohmann::json> rows;
  const int total = static_cast<int>(seeds.size());
  for (const std::uint64_t seed : seeds) {
    auto it = done.find(seed);
    if (it != done.end()) {
      if (checkDone) checkDone(it->second);
      rows.push_back(it->second);
    } else {
      nlohmann::json row = run(seed);
      if (onRow) onRow(row);
      rows.push_back(std::move(row));
    }
    if (progress) progress(rows.back(), static_cast<int>(rows.size()), total);
  }
  return rows;
}

}  // namespace nao::sim
