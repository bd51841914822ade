#include "apps/Rows.h"

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "robot/Error.h"

namespace nao::cli {

std::vector<nlohmann::json> readRows(const std::string& path, const std::string& command) {
  std::vector<nlohmann::json> rows;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return rows;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("--rows", path + ": cannot be read");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  std::size_t pos = 0, line = 0;
  while (pos < text.size()) {
    const std::size_t end = text.find('\n', pos);
    ++line;
    const std::string s = text.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
    const bool last = end == std::string::npos || end + 1 >= text.size();
    auto j = nlohmann::json::parse(s, nullptr, false);
    const bool ok = !j.is_discarded() && j.is_object() && j.contains("seed") && j.contains("settings");
    if (end == std::string::npos || (!ok && last)) {
      if (ok && end == std::string::npos) {  // a complete row without its newline: keep it, end the line
        std::ofstream(path, std::ios::app) << '\n';
        rows.push_back(std::move(j));
        break;
      }
      std::fprintf(stderr, "%s: %s: line %zu is truncated (%zu bytes); its trial runs again\n", command.c_str(),
                   path.c_str(), line, s.size());
      std::filesystem::resize_file(path, pos, ec);
      if (ec) throw Error("--rows", path + ": cannot be truncated (" + ec.message() + ")");
      break;
    }
    if (!ok) throw Error("--rows", path + ": line " + std::to_string(line) + " is not a row of " + command);
    rows.push_back(std::move(j));
    pos = end + 1;
  }
  return rows;
}

RowWriter::RowWriter(const std::string& path) : path_(path) {
  if (path_.empty()) return;
  file_.open(path_, std::ios::app | std::ios::binary);
  if (!file_) throw RunFailure(path_, "cannot be opened for appending");
}

void RowWriter::operator()(const nlohmann::json& row) {
  if (path_.empty()) return;
  file_ << row.dump() << '\n';
  file_.flush();
  if (!file_) throw RunFailure(path_, "cannot be written");
}

}  // namespace nao::cli
