#pragma once
// The rows of a resumable evaluation (eval localization, challenge, match; the files are read and
// written by apps/Rows.h, split over machines by apps/Batch.h): which seeds a run has, the rows
// already done by seed, and the loop that runs the others.
#include <cstdint>
#include <functional>
#include <map>
#include <vector>

#include <nlohmann/json.hpp>

namespace nao::sim {

// The seeds of a run: `list` when it is not empty (batch chunks, --seeds), else `count` seeds
// from `first` on. Throws nao::Error(countFlag) for a count below 1.
std::vector<std::uint64_t> trialSeeds(std::uint64_t first, int count, const std::vector<std::uint64_t>& list,
                                      const char* countFlag);

// Throws nao::Error("--rows", ...) for a row without seed or settings, or of other settings.
std::map<std::uint64_t, nlohmann::json> rowsBySeed(std::vector<nlohmann::json> rows, const nlohmann::json& settings);

// For each seed in order: its row from `done` (after `checkDone`, which throws for a row that
// does not fit), or a new one from `run`, handed to `onRow` as it ends; `progress` after each.
// Returns the rows in the order of `seeds`.
std::vector<nlohmann::json> collectRows(const std::vector<std::uint64_t>& seeds, std::map<std::uint64_t, nlohmann::json> done,
                                        const std::function<nlohmann::json(std::uint64_t seed)>& run,
                                        const std::function<void(const nlohmann::json& row)>& onRow,
                                        const std::function<void(const nlohmann::json& row, int done, int total)>& progress,
                                        const std::function<void(const nlohmann::json& row)>& checkDone = {});

}  // namespace nao::sim
