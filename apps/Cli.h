#pragma once
// Command-line parsing shared by every subcommand: declared options only (an unknown flag is
// bad usage, exit 2), typed getters that name the flag in their error, JSON output to a file
// or stdout, and the numeric formats people type (--pose X,Y,THETA_DEG).
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace nao::cli {

struct Option {
  std::string name;   // without the leading dashes
  std::string value;  // metavariable, empty for a switch
  std::string help;
};

class Args {
 public:
  // Throws nao::Error("--flag", ...) for unknown flags, missing values, or stray positionals
  // beyond maxPositional.
  Args(const std::string& command, const std::vector<std::string>& argv, std::vector<Option> options,
       int maxPositional = 0);

  bool has(const std::string& name) const { return values_.count(name) != 0; }
  bool helpRequested() const { return help_; }
  std::string usage() const;

  std::string str(const std::string& name, const std::string& fallback) const;
  double num(const std::string& name, double fallback) const;
  long integer(const std::string& name, long fallback) const;
  std::uint64_t seed() const { return static_cast<std::uint64_t>(integer("seed", 1)); }
  // A comma-separated list of exactly n numbers.
  std::vector<double> list(const std::string& name, std::size_t n) const;
  std::optional<std::vector<double>> optionalList(const std::string& name, std::size_t n) const;
  const std::vector<std::string>& positional() const { return positional_; }

 private:
  std::string command_;
  std::vector<Option> options_;
  std::map<std::string, std::string> values_;
  std::vector<std::string> positional_;
  bool help_ = false;
};

// Options every subcommand takes.
std::vector<Option> commonOptions();

// Writes j to `target` ("-" = stdout); throws nao::Error(target, ...) if the file cannot be written.
void writeJson(const std::string& target, const nlohmann::json& j);

// Progress on stderr, one line, overwritten in place when stderr is a terminal.
void progress(const std::string& what, std::size_t done, std::size_t total);

}  // namespace nao::cli
