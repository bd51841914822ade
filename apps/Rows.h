#pragma once
// --rows FILE for evaluations that span sessions (eval localization, eval challenge): one JSON
// line per trial, appended and flushed as the trial ends, read back on the next run so that only
// the missing seeds run.
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace nao::cli {

// The rows already in `path` (none when it does not exist). A last line that is cut short (no
// newline, or not JSON) is a trial interrupted while its row was written: it is reported on
// stderr, removed from the file and its trial runs again. Any other line that is not a row
// (an object with "seed" and "settings") is bad input: nao::Error("--rows", ...) naming the
// file, the line and `command`.
std::vector<nlohmann::json> readRows(const std::string& path, const std::string& command);

// Appends rows to `path` (nothing when the path is empty); each row is flushed at once.
class RowWriter {
 public:
  explicit RowWriter(const std::string& path);
  void operator()(const nlohmann::json& row);

 private:
  std::string path_;
  std::ofstream file_;
};

}  // namespace nao::cli
