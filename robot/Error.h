#pragma once
// One error type for bad input: it carries the file (or flag) and the field at fault so
// that the command can print exactly one line and exit 2. Libraries throw it; only apps/
// decides how the process ends.
#include <stdexcept>
#include <string>

namespace nao {

class Error : public std::runtime_error {
 public:
  // where: a file path, a flag (--pose) or a packet name; what: the problem, e.g. "field.length: must be > 0".
  Error(std::string where, const std::string& what)
      : std::runtime_error(where.empty() ? what : where + ": " + what), where_(std::move(where)) {}
  const std::string& where() const { return where_; }

 private:
  std::string where_;
};

// A run that could not finish for a reason outside the input: a file that cannot be written
// (a full disk), an engine error. Exit 1 with one line naming `where`.
class RunFailure : public std::runtime_error {
 public:
  RunFailure(std::string where, const std::string& what)
      : std::runtime_error(where.empty() ? what : where + ": " + what), where_(std::move(where)) {}
  const std::string& where() const { return where_; }

 private:
  std::string where_;
};

}  // namespace nao
