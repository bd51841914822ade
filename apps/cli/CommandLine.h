#pragma once
// The nao-soccer command line, declared on CLI11. Every command declares exactly the options it
// uses, each with its type, unit, range, default and relations; --help is generated from the
// declarations, and a value outside them is bad usage: exit 2 with one line naming the option.
// Bounds that depend on the field file (a pose on the field) are declared here too and checked
// once the field is loaded (checkPlaces). Nothing else in apps/ parses a number.
#include <cstdint>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "robot/Text.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace nao {
struct FieldDimensions;
}

namespace nao::cli {

// What the contract test and the argv fuzzer know of one declared option.
struct OptionSpec {
  enum class Kind { Switch, Number, Count, Choice, Numbers, InputFile, OutputFile, OutputFolder, Text };
  struct Element {
    std::string name, unit;
    double lo = 0, hi = 0;
  };
  std::string flag;  // "--seconds", or the positional's name
  Kind kind = Kind::Text;
  double lo = 0, hi = 0;             // Number and Count
  std::string unit;                  // Number
  std::vector<std::string> choices;  // Choice
  std::vector<Element> elements;     // Numbers
  bool positional = false;
};

// An option that names a place on the field: its x and y must lie on the field or its border.
struct FieldPlace {
  std::string flag;
  const std::vector<double>* value;  // x, y, ... in m (empty when not given)
  double margin = 0;                 // beyond the border strip, m
};

// The options every command shares; which of them a command takes is its declaration's choice.
struct CommonOptions {
  std::uint32_t seed = 1;
  std::string json;   // "" = no JSON, "-" = stdout
  std::string field;  // "" = the command's default field
  std::string gl = "osmesa";  // --gl: the OpenGL the cameras render through (sim/GlContext.h)
  std::vector<FieldPlace> places;
  std::set<std::string> given;  // the flags on the command line
  bool has(const std::string& flag) const { return given.count(flag) != 0; }
};

class Command {
 public:
  Command(CLI::App* app, std::string path, CommonOptions& common);

  const std::string& path() const { return path_; }  // "eval perception"
  CLI::App* app() const { return app_; }
  const std::vector<OptionSpec>& specs() const { return specs_; }
  CommonOptions& common() { return common_; }

  // Declarations. `help` says what it is; the range, unit and default are added to it.
  void seed();
  void json();
  void field(const std::string& defaultText);
  void gl();  // --gl auto|egl|osmesa, on every command that renders
  CLI::Option* flag(const std::string& name, bool& value, const std::string& help);
  CLI::Option* number(const std::string& name, double& value, double lo, double hi, const std::string& unit,
                      const std::string& help);
  CLI::Option* count(const std::string& name, int& value, int lo, int hi, const std::string& help);
  CLI::Option* choice(const std::string& name, std::string& value, std::vector<std::string> choices,
                      const std::string& help);
  // One of `choices`, or a value `other` accepts (it returns the problem, or "" when fine):
  // --cameras none|v4l2|files:DIR.
  CLI::Option* choice(const std::string& name, std::string& value, std::vector<std::string> choices,
                      const std::string& help, const std::string& otherName,
                      std::function<std::string(const std::string&)> other);
  // Comma-separated numbers, each with its own name, unit and range: --pose X,Y,THETA.
  CLI::Option* numbers(const std::string& name, std::vector<double>& value, std::vector<OptionSpec::Element> elements,
                       const std::string& help);
  // One of `choices`, or comma-separated numbers as for numbers(): --miscalibration none|random|6 numbers.
  CLI::Option* choiceOrNumbers(const std::string& name, std::string& choice, std::vector<double>& value,
                               std::vector<std::string> choices, std::vector<OptionSpec::Element> elements,
                               const std::string& help);
  // An image size WIDTHxHEIGHT in pixels (width even: YUYV pairs).
  CLI::Option* size(const std::string& name, int& width, int& height, const std::string& help);
  // A list of seeds: "1-40,45,50-52" (ranges inclusive), each 0..4294967295 + 10^6 (a range's
  // run of `--seed N --trials M` goes past 2^32), none twice, at most 100000 in all.
  CLI::Option* seedList(const std::string& name, std::vector<std::uint64_t>& value, const std::string& help);
  CLI::Option* inputFile(const std::string& name, std::string& value, const std::string& help);
  CLI::Option* outputFile(const std::string& name, std::string& value, const std::string& help);
  CLI::Option* outputFolder(const std::string& name, std::string& value, const std::string& help);
  // Free text checked by `check` (returns the problem, or "" when fine).
  CLI::Option* text(const std::string& name, std::string& value, const std::string& metavar, const std::string& help,
                    std::function<std::string(const std::string&)> check = {});
  CLI::Option* positionalFile(const std::string& name, std::string& value, const std::string& help);

  // Relations checked after parsing; `rule` returns "--flag: problem" or "".
  void rule(std::function<std::string()> check) { rules_.push_back(std::move(check)); }
  // These flags are only for the given value of `selector` (e.g. --backend nao).
  void onlyWith(const std::string& selector, const std::string& selectorValue, const std::string& currentValueOf,
                std::vector<std::string> flags);
  // A place on the field (checked when the field is loaded).
  void onField(const std::string& flag, const std::vector<double>& value, double margin = 0);

  // Called by CommandLine after a successful parse: records the given flags, converts the
  // numbers lists, checks the rules. Throws nao::Error.
  void finish();

  std::function<int()> run;  // set by apps/main.cpp

 private:
  CLI::Option* add(const std::string& name, std::string& raw, const std::string& help, OptionSpec spec,
                   std::function<std::string(const std::string&)> check);

  CLI::App* app_;
  std::string path_;
  CommonOptions& common_;
  std::vector<OptionSpec> specs_;
  std::vector<std::function<std::string()>> rules_;
  std::vector<std::function<void()>> converters_;
  std::vector<std::unique_ptr<std::string>> raw_;
};

// Checks every declared FieldPlace against the field; throws nao::Error("--flag", ...).
void checkPlaces(const CommonOptions& common, const FieldDimensions& field);

struct Options;  // apps/cli/Options.h

class CommandLine {
 public:
  // The whole of a command's life: parse argv, print help, or run the chosen command's body
  // inside an io::OutputTransaction; returns the exit code (0 success; 1 a failed run:
  // RunFailure or another exception; 2 bad usage or input: nao::Error), having printed at most
  // one line "nao-soccer <command>: <what>" on stderr.
  int main(int argc, const char* const* argv);

  CommandLine();  // declares every command (apps/cli/Declarations.cpp)
  ~CommandLine();

  // The command chosen by argv (argv[0] is the program), or nullptr when help was printed to
  // `help`. Throws nao::Error("--flag" or the command, ...) for bad usage.
  Command* parse(int argc, const char* const* argv, std::string& help);

  // The command (or group) the last parse reached, "" for none: names it in an error line.
  const std::string& parsedPath() const { return parsedPath_; }
  Options& options() { return *options_; }
  std::vector<Command*> commands() const;  // the leaves: render, eval perception, ...
  Command* command(const std::string& path) const;
  std::string rootHelp() const;

 private:
  std::unique_ptr<CLI::App> root_;
  std::unique_ptr<Options> options_;
  std::vector<std::unique_ptr<Command>> commands_;
  std::string parsedPath_;
  void declare();  // apps/cli/Declarations.cpp
  Command& leaf(CLI::App* parent, const std::string& name, const std::string& summary, CommonOptions& common);
  CLI::App* group(const std::string& name, const std::string& summary);
};

using nao::escapeControl;

}  // namespace nao::cli
