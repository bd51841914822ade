#include "apps/Cli.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "robot/Error.h"

namespace nao::cli {

std::vector<Option> commonOptions() {
  return {{"seed", "N", "random seed (same seed, same result)"},
          {"json", "FILE", "write the result as JSON to FILE ('-' = stdout)"},
          {"field", "FILE", "field_dimensions.json (default config/field_dimensions.json)"}};
}

Args::Args(const std::string& command, const std::vector<std::string>& argv, std::vector<Option> options,
           int maxPositional)
    : command_(command), options_(std::move(options)) {
  for (std::size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a == "--help" || a == "-h") {
      help_ = true;
      continue;
    }
    if (a.rfind("--", 0) == 0 && a.size() > 2) {
      std::string name = a.substr(2), value;
      bool inlineValue = false;
      if (auto eq = name.find('='); eq != std::string::npos) {
        value = name.substr(eq + 1);
        name = name.substr(0, eq);
        inlineValue = true;
      }
      const Option* opt = nullptr;
      for (const auto& o : options_)
        if (o.name == name) opt = &o;
      if (!opt) throw Error("--" + name, "unknown option for '" + command_ + "' (see nao-soccer " + command_ + " --help)");
      if (!opt->value.empty() && !inlineValue) {
        if (i + 1 >= argv.size()) throw Error("--" + name, "needs a value " + opt->value);
        value = argv[++i];
      } else if (opt->value.empty() && inlineValue) {
        throw Error("--" + name, "takes no value");
      }
      values_[name] = value;
      continue;
    }
    if (static_cast<int>(positional_.size()) >= maxPositional)
      throw Error(a, "unexpected argument for '" + command_ + "'");
    positional_.push_back(a);
  }
}

std::string Args::usage() const {
  std::ostringstream s;
  s << "usage: nao-soccer " << command_ << " [options]\n";
  for (const auto& o : options_) {
    std::string flag = "--" + o.name + (o.value.empty() ? "" : " " + o.value);
    s << "  " << flag << std::string(flag.size() < 28 ? 28 - flag.size() : 1, ' ') << o.help << "\n";
  }
  return s.str();
}

std::string Args::str(const std::string& name, const std::string& fallback) const {
  auto it = values_.find(name);
  return it == values_.end() ? fallback : it->second;
}

static double parseNumber(const std::string& flag, const std::string& text) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(v)) throw Error(flag, "'" + text + "' is not a finite number");
  return v;
}

double Args::num(const std::string& name, double fallback) const {
  auto it = values_.find(name);
  return it == values_.end() ? fallback : parseNumber("--" + name, it->second);
}

long Args::integer(const std::string& name, long fallback) const {
  auto it = values_.find(name);
  if (it == values_.end()) return fallback;
  std::size_t used = 0;
  long v = 0;
  try {
    v = std::stol(it->second, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != it->second.size()) throw Error("--" + name, "'" + it->second + "' is not an integer");
  return v;
}

std::optional<std::vector<double>> Args::optionalList(const std::string& name, std::size_t n) const {
  auto it = values_.find(name);
  if (it == values_.end()) return std::nullopt;
  std::vector<double> out;
  std::stringstream ss(it->second);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(parseNumber("--" + name, item));
  if (out.size() != n)
    throw Error("--" + name, "needs " + std::to_string(n) + " comma-separated numbers, got '" + it->second + "'");
  return out;
}

std::vector<double> Args::list(const std::string& name, std::size_t n) const {
  auto v = optionalList(name, n);
  if (!v) throw Error("--" + name, "is required");
  return *v;
}

void writeJson(const std::string& target, const nlohmann::json& j) {
  if (target == "-") {
    std::cout << j.dump(2) << std::endl;
    return;
  }
  std::ofstream f(target);
  if (!f) throw Error(target, "cannot open for writing");
  f << j.dump(2) << "\n";
  if (!f) throw Error(target, "write failed");
}

void progress(const std::string& what, std::size_t done, std::size_t total) {
  static const bool tty = isatty(fileno(stderr));
  if (tty) {
    std::fprintf(stderr, "\r%s %zu/%zu", what.c_str(), done, total);
    if (done == total) std::fputc('\n', stderr);
  } else if (done == total || total < 20 || done % (total / 10) == 0) {
    std::fprintf(stderr, "%s %zu/%zu\n", what.c_str(), done, total);
  }
}

}  // namespace nao::cli
