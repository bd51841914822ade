#pragma once
// What every command's body shares: the JSON result, progress on stderr.
#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

namespace nao::cli {

// Writes j to `target` ("-" = stdout, which then carries nothing else) through robot/OutputFiles.h;
// throws nao::RunFailure naming the file (or stdout) when it cannot be written.
void writeJson(const std::string& target, const nlohmann::json& j);

// Progress on stderr, one line, overwritten in place when stderr is a terminal.
void progress(const std::string& what, std::size_t done, std::size_t total);

}  // namespace nao::cli
