#pragma once
// The rows of a resumable evaluation (eval localization, eval challenge; the files are read and
// written by apps/Rows.h): the rows already done, by seed, each checked to carry this run's
// settings. Throws nao::Error("--rows", ...) for a row without seed or settings, or of other
// settings.
#include <cstdint>
#include <map>
#include <vector>

#include <nlohmann/json.hpp>

namespace nao::sim {

std::map<std::uint64_t, nlohmann::json> rowsBySeed(std::vector<nlohmann::json> rows, const nlohmann::json& settings);

}  // namespace nao::sim
