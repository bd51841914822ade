#pragma once
// What every command's body shares: the JSON result, progress on stderr.
#include <cstddef>
#include <fstream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "apps/cli/Options.h"
#include "robot/Debug.h"

namespace nao::cli {

// Writes j to `target` ("-" = stdout, which then carries nothing else) through robot/OutputFiles.h;
// throws nao::RunFailure naming the file (or stdout) when it cannot be written.
void writeJson(const std::string& target, const nlohmann::json& j);

// The debug channels a command's --debug subscribed, writing to --debug-out (else stderr). The
// file is written line by line as the run goes, not staged with the command's other outputs: a
// run that fails keeps its trace. channels() is null when --debug was not given.
class DebugSink {
 public:
  // Throws nao::RunFailure naming the file when it cannot be opened.
  explicit DebugSink(const DebugOptions& options);
  DebugChannels* channels() { return channels_.get(); }

 private:
  std::ofstream file_;
  std::unique_ptr<DebugChannels> channels_;
};

// Progress on stderr, one line, overwritten in place when stderr is a terminal.
void progress(const std::string& what, std::size_t done, std::size_t total);

}  // namespace nao::cli
