#include "apps/cli/CommandLine.h"

#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <CLI/CLI.hpp>

#include "apps/cli/Options.h"
#include "perception/FieldDimensions.h"
#include "robot/Error.h"
#include "robot/OutputFiles.h"

namespace nao::cli {

namespace {

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

std::string join(const std::vector<std::string>& items, const std::string& sep) {
  std::string out;
  for (const auto& i : items) out += (out.empty() ? "" : sep) + i;
  return out;
}

std::string rangeText(double lo, double hi, const std::string& unit) {
  return fmt(lo) + ".." + fmt(hi) + (unit.empty() ? "" : " " + unit);
}

// A whole decimal number (no trailing text, finite); "" when fine.
std::string parseReal(const std::string& text, double& out) {
  if (text.empty()) return "an empty value is not a number";
  errno = 0;
  char* end = nullptr;
  out = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0') return quoted(text) + " is not a number";
  if (!std::isfinite(out) || errno == ERANGE) return quoted(text) + " is not a finite number";
  return "";
}

std::string parseInteger(const std::string& text, long long& out) {
  if (text.empty()) return "an empty value is not a whole number";
  errno = 0;
  char* end = nullptr;
  out = std::strtoll(text.c_str(), &end, 10);
  if (end == text.c_str() || *end != '\0') return quoted(text) + " is not a whole number";
  if (errno == ERANGE) return quoted(text) + " is far outside the range";
  return "";
}

std::string inputFileProblem(const std::string& path) {
  if (path.empty()) return "an empty file name";
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) return quoted(path) + ": file not found";
  if (std::filesystem::is_directory(status)) return quoted(path) + " is a folder, not a file";
  // A device or a FIFO would block or never end (/dev/stdin, /dev/zero).
  if (!std::filesystem::is_regular_file(status)) return quoted(path) + " is not a regular file";
  if (::access(path.c_str(), R_OK) != 0) return quoted(path) + " cannot be read";
  constexpr std::uintmax_t kMaxInput = 1ull << 30;  // no input of ours comes near 1 GiB
  if (std::filesystem::file_size(path, ec) > kMaxInput) return quoted(path) + " is larger than 1 GiB";
  return "";
}

std::string numbersProblem(const std::string& s, const std::vector<OptionSpec::Element>& elements,
                           const std::string& metavar) {
  std::vector<std::string> parts;
  std::size_t from = 0;
  while (true) {
    const std::size_t comma = s.find(',', from);
    parts.push_back(s.substr(from, comma == std::string::npos ? std::string::npos : comma - from));
    if (comma == std::string::npos) break;
    from = comma + 1;
  }
  if (parts.size() != elements.size())
    return "needs " + std::to_string(elements.size()) + " comma-separated numbers " + metavar + ", not " + quoted(s);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    double v = 0;
    if (auto p = parseReal(parts[i], v); !p.empty()) return elements[i].name + ": " + p;
    if (v < elements[i].lo || v > elements[i].hi)
      return elements[i].name + " " + parts[i] + " is outside " + rangeText(elements[i].lo, elements[i].hi, elements[i].unit);
  }
  return "";
}

// The numbers of a checked list.
std::vector<double> splitNumbers(const std::string& raw) {
  std::vector<double> value;
  const char* p = raw.c_str();
  while (true) {
    char* end = nullptr;
    value.push_back(std::strtod(p, &end));
    if (*end != ',') break;
    p = end + 1;
  }
  return value;
}

OptionSpec specOf(OptionSpec::Kind kind, const std::string& flag = "") {
  OptionSpec spec;
  spec.kind = kind;
  spec.flag = flag;
  return spec;
}

CLI::Validator validator(std::function<std::string(const std::string&)> check) {
  return CLI::Validator([check = std::move(check)](std::string& value) { return check(value); }, "", "");
}

}  // namespace

Command::Command(CLI::App* app, std::string path, CommonOptions& common)
    : app_(app), path_(std::move(path)), common_(common) {}

CLI::Option* Command::add(const std::string& name, std::string& raw, const std::string& help, OptionSpec spec,
                          std::function<std::string(const std::string&)> check) {
  spec.flag = name;
  specs_.push_back(spec);
  CLI::Option* o = app_->add_option(name, raw, help);
  if (check) o->check(validator(std::move(check)));
  return o;
}

void Command::seed() {
  auto* raw = raw_.emplace_back(std::make_unique<std::string>()).get();
  OptionSpec spec = specOf(OptionSpec::Kind::Count);
  spec.lo = 0;
  spec.hi = 4294967295.0;
  add("--seed", *raw, "random seed: the same seed gives the same result; 0..4294967295 (default 1)", spec,
      [](const std::string& s) {
        long long v = 0;
        if (auto p = parseInteger(s, v); !p.empty()) return p;
        return v < 0 || v > 4294967295LL ? s + " is outside 0..4294967295" : std::string();
      })
      ->type_name("N");
  converters_.push_back([this, raw] {
    if (!raw->empty()) common_.seed = static_cast<std::uint32_t>(std::strtoll(raw->c_str(), nullptr, 10));
  });
}

void Command::json() {
  outputFile("--json", common_.json, "write the result as JSON to FILE ('-': stdout, which then carries nothing else)")
      ->type_name("FILE|-");
}

void Command::gl() {
  choice("--gl", common_.gl, {"auto", "egl", "osmesa"},
         "the OpenGL the cameras render through: EGL (a GPU's device, MUJOCO_EGL_DEVICE_ID picks one by index; "
         "else Mesa's software device or the surfaceless platform) or OSMesa; auto: EGL where it starts, else OSMesa "
         "(on a CPU both are Mesa's llvmpipe and render the same bytes)");
}

void Command::field(const std::string& defaultText) {
  inputFile("--field", common_.field, "the field: a field_dimensions.json (default " + defaultText + ")");
}

CLI::Option* Command::flag(const std::string& name, bool& value, const std::string& help) {
  specs_.push_back(specOf(OptionSpec::Kind::Switch, name));
  return app_->add_flag(name, value, help)->disable_flag_override();
}

CLI::Option* Command::number(const std::string& name, double& value, double lo, double hi, const std::string& unit,
                             const std::string& help) {
  auto* raw = raw_.emplace_back(std::make_unique<std::string>()).get();
  OptionSpec spec = specOf(OptionSpec::Kind::Number);
  spec.lo = lo;
  spec.hi = hi;
  spec.unit = unit;
  auto* o = add(name, *raw, help + "; " + rangeText(lo, hi, unit) + " (default " + fmt(value) + ")", spec,
                [lo, hi, unit](const std::string& s) {
                  double v = 0;
                  if (auto p = parseReal(s, v); !p.empty()) return p;
                  return v < lo || v > hi ? s + " is outside " + rangeText(lo, hi, unit) : std::string();
                });
  converters_.push_back([raw, &value] {
    if (!raw->empty()) value = std::strtod(raw->c_str(), nullptr);
  });
  std::string metavar = unit.empty() ? "X" : unit;
  for (char& ch : metavar) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  return o->type_name(metavar);
}

CLI::Option* Command::count(const std::string& name, int& value, int lo, int hi, const std::string& help) {
  auto* raw = raw_.emplace_back(std::make_unique<std::string>()).get();
  OptionSpec spec = specOf(OptionSpec::Kind::Count);
  spec.lo = lo;
  spec.hi = hi;
  auto* o = add(name, *raw, help + "; " + std::to_string(lo) + ".." + std::to_string(hi) + " (default " +
                                std::to_string(value) + ")",
                spec, [lo, hi](const std::string& s) {
                  long long v = 0;
                  if (auto p = parseInteger(s, v); !p.empty()) return p;
                  return v < lo || v > hi ? s + " is outside " + std::to_string(lo) + ".." + std::to_string(hi)
                                          : std::string();
                });
  converters_.push_back([raw, &value] {
    if (!raw->empty()) value = static_cast<int>(std::strtoll(raw->c_str(), nullptr, 10));
  });
  return o->type_name("N");
}

CLI::Option* Command::choice(const std::string& name, std::string& value, std::vector<std::string> choices,
                             const std::string& help) {
  OptionSpec spec = specOf(OptionSpec::Kind::Choice);
  spec.choices = choices;
  const std::string names = join(choices, "|");
  return add(name, value, help + (value.empty() ? "" : " (default " + value + ")"), spec,
             [choices, names](const std::string& s) {
               for (const auto& c : choices)
                 if (s == c) return std::string();
               return quoted(s) + " is not one of " + names;
             })
      ->type_name(names);
}

CLI::Option* Command::choice(const std::string& name, std::string& value, std::vector<std::string> choices,
                             const std::string& help, const std::string& otherName,
                             std::function<std::string(const std::string&)> other) {
  OptionSpec spec = specOf(OptionSpec::Kind::Choice);
  spec.choices = choices;
  const std::string names = join(choices, "|") + "|" + otherName;
  return add(name, value, help + (value.empty() ? "" : " (default " + value + ")"), spec,
             [choices, names, other](const std::string& s) {
               for (const auto& c : choices)
                 if (s == c) return std::string();
               const std::string problem = other(s);
               return problem.empty() ? problem : quoted(s) + ": " + problem + " (" + names + ")";
             })
      ->type_name(names);
}

CLI::Option* Command::numbers(const std::string& name, std::vector<double>& value,
                              std::vector<OptionSpec::Element> elements, const std::string& help) {
  auto* raw = raw_.emplace_back(std::make_unique<std::string>()).get();
  std::vector<std::string> names, ranges;
  for (const auto& e : elements) {
    names.push_back(e.name);
    ranges.push_back(e.name + " " + rangeText(e.lo, e.hi, e.unit));
  }
  const std::string metavar = join(names, ",");
  OptionSpec spec = specOf(OptionSpec::Kind::Numbers);
  spec.elements = elements;
  auto* o = add(name, *raw, help + "; " + join(ranges, ", "), spec,
                [elements, metavar](const std::string& s) { return numbersProblem(s, elements, metavar); });
  converters_.push_back([raw, &value] {
    if (!raw->empty()) value = splitNumbers(*raw);
  });
  return o->type_name(metavar);
}

CLI::Option* Command::choiceOrNumbers(const std::string& name, std::string& choice, std::vector<double>& value,
                                      std::vector<std::string> choices, std::vector<OptionSpec::Element> elements,
                                      const std::string& help) {
  auto* raw = raw_.emplace_back(std::make_unique<std::string>()).get();
  std::vector<std::string> names;
  for (const auto& e : elements) names.push_back(e.name);
  const std::string metavar = join(names, ",");
  OptionSpec spec = specOf(OptionSpec::Kind::Numbers);
  spec.choices = choices;
  spec.elements = elements;
  auto* o = add(name, *raw, help + " (default " + choice + ")", spec, [choices, elements, metavar](const std::string& s) {
    for (const auto& c : choices)
      if (s == c) return std::string();
    if (s.find(',') == std::string::npos)
      return quoted(s) + " is not one of " + join(choices, ", ") + " nor " + std::to_string(elements.size()) + " numbers " + metavar;
    return numbersProblem(s, elements, metavar);
  });
  converters_.push_back([raw, &choice, &value, choices] {
    if (raw->empty()) return;
    for (const auto& c : choices)
      if (*raw == c) {
        choice = c;
        return;
      }
    choice = "numbers";
    value = splitNumbers(*raw);
  });
  return o->type_name(join(choices, "|") + "|" + metavar);
}

namespace {

constexpr long long kMaxSeed = 4294967295LL + 1000000;
constexpr std::size_t kMaxSeeds = 100000;

// "" when fine, else the problem; the seeds in order of the list.
std::string seedListProblem(const std::string& s, std::vector<std::uint64_t>* out) {
  std::vector<std::uint64_t> seeds;
  std::set<std::uint64_t> seen;
  std::size_t pos = 0;
  while (true) {
    const std::size_t comma = std::min(s.find(',', pos), s.size());
    const std::string item = s.substr(pos, comma - pos);
    const std::size_t dash = item.find('-', 1);
    long long a = 0, b = 0;
    if (auto p = parseInteger(item.substr(0, dash), a); !p.empty()) return p + " (a seed list: 1-40,45)";
    b = a;
    if (dash != std::string::npos)
      if (auto p = parseInteger(item.substr(dash + 1), b); !p.empty()) return p + " (a seed list: 1-40,45)";
    if (a < 0 || b > kMaxSeed) return quoted(item) + " is outside 0.." + std::to_string(kMaxSeed);
    if (b < a) return quoted(item) + " is a range that goes down";
    if (static_cast<std::size_t>(b - a) >= kMaxSeeds || seeds.size() + static_cast<std::size_t>(b - a) >= kMaxSeeds)
      return "more than " + std::to_string(kMaxSeeds) + " seeds";
    for (long long v = a; v <= b; ++v) {
      if (!seen.insert(static_cast<std::uint64_t>(v)).second) return "seed " + std::to_string(v) + " is listed twice";
      seeds.push_back(static_cast<std::uint64_t>(v));
    }
    if (comma >= s.size()) break;
    pos = comma + 1;
  }
  if (out) *out = std::move(seeds);
  return "";
}

}  // namespace

CLI::Option* Command::seedList(const std::string& name, std::vector<std::uint64_t>& value, const std::string& help) {
  auto* raw = raw_.emplace_back(std::make_unique<std::string>()).get();
  auto* o = add(name, *raw, help + "; a list like 1-40,45 (ranges inclusive), each seed once", specOf(OptionSpec::Kind::Text),
                [](const std::string& s) { return seedListProblem(s, nullptr); });
  converters_.push_back([raw, &value] {
    if (!raw->empty()) seedListProblem(*raw, &value);
  });
  return o->type_name("LIST");
}

CLI::Option* Command::size(const std::string& name, int& width, int& height, const std::string& help) {
  auto* raw = raw_.emplace_back(std::make_unique<std::string>()).get();
  OptionSpec spec = specOf(OptionSpec::Kind::Numbers);
  spec.elements = {{"WIDTH", "px", 2, 8192}, {"HEIGHT", "px", 1, 8192}};
  auto* o = add(name, *raw, help + "; 2..8192 x 1..8192 px, even width", spec, [](const std::string& s) {
    const auto x = s.find('x');
    long long w = 0, h = 0;
    if (x == std::string::npos || !parseInteger(s.substr(0, x), w).empty() || !parseInteger(s.substr(x + 1), h).empty())
      return "needs WIDTHxHEIGHT in pixels, not " + quoted(s);
    if (w < 2 || w > 8192 || h < 1 || h > 8192) return quoted(s) + " is outside 2..8192 x 1..8192 px";
    if (w % 2) return quoted(s) + ": the width must be even (YUYV pairs)";
    return std::string();
  });
  converters_.push_back([raw, &width, &height] {
    if (raw->empty()) return;
    width = static_cast<int>(std::strtol(raw->c_str(), nullptr, 10));
    height = static_cast<int>(std::strtol(raw->c_str() + raw->find('x') + 1, nullptr, 10));
  });
  return o->type_name("WIDTHxHEIGHT");
}

CLI::Option* Command::inputFile(const std::string& name, std::string& value, const std::string& help) {
  return add(name, value, help, specOf(OptionSpec::Kind::InputFile), inputFileProblem)->type_name("FILE");
}

CLI::Option* Command::positionalFile(const std::string& name, std::string& value, const std::string& help) {
  OptionSpec spec = specOf(OptionSpec::Kind::InputFile, name);
  spec.positional = true;
  specs_.push_back(spec);
  return app_->add_option(name, value, help)->required()->check(validator(inputFileProblem))->type_name("FILE");
}

CLI::Option* Command::outputFile(const std::string& name, std::string& value, const std::string& help) {
  const bool stdoutAllowed = name == "--json";
  return add(name, value, help, specOf(OptionSpec::Kind::OutputFile),
             [stdoutAllowed](const std::string& s) {
               if (stdoutAllowed && s == "-") return std::string();
               const std::string p = io::outputFileProblem(s);
               return p.empty() ? p : (s.empty() ? p : quoted(s) + ": " + p);
             })
      ->type_name("FILE");
}

CLI::Option* Command::outputFolder(const std::string& name, std::string& value, const std::string& help) {
  return add(name, value, help, specOf(OptionSpec::Kind::OutputFolder),
             [](const std::string& s) {
               const std::string p = io::outputDirectoryProblem(s);
               return p.empty() ? p : (s.empty() ? p : quoted(s) + ": " + p);
             })
      ->type_name("DIR");
}

CLI::Option* Command::text(const std::string& name, std::string& value, const std::string& metavar,
                           const std::string& help, std::function<std::string(const std::string&)> check) {
  return add(name, value, help, specOf(OptionSpec::Kind::Text), std::move(check))->type_name(metavar);
}

void Command::onlyWith(const std::string& selectorFlag, const std::string& selectorValue, const std::string& selector,
                       std::vector<std::string> flags) {
  rule([this, selectorFlag, selectorValue, &selector, flags] {
    if (selector == selectorValue) return std::string();
    for (const auto& f : flags)
      if (common_.has(f)) return f + ": only with " + selectorFlag + " " + selectorValue;
    return std::string();
  });
}

void Command::onField(const std::string& flag, const std::vector<double>& value, double margin) {
  common_.places.push_back({flag, &value, margin});
  CLI::Option* o = app_->get_option(flag);
  o->description(o->get_description() + "; X and Y on the field or its border strip");
}

void Command::finish() {
  common_.given.clear();
  for (const CLI::Option* o : app_->get_options())
    if (o->count() > 0) common_.given.insert(o->get_name());
  for (auto& convert : converters_) convert();
  for (auto& check : rules_)
    if (auto problem = check(); !problem.empty()) {
      const auto colon = problem.find(": ");
      throw Error(problem.substr(0, colon), colon == std::string::npos ? "" : problem.substr(colon + 2));
    }
}

void checkPlaces(const CommonOptions& common, const FieldDimensions& field) {
  for (const auto& p : common.places) {
    if (p.value->size() < 2) continue;
    const double xMax = field.length / 2 + field.borderStripWidth + p.margin;
    const double yMax = field.width / 2 + field.borderStripWidth + p.margin;
    const double x = (*p.value)[0], y = (*p.value)[1];
    if (std::abs(x) > xMax || std::abs(y) > yMax)
      throw Error(p.flag, "(" + fmt(x) + ", " + fmt(y) + ") m is off this field and its border (|x| <= " + fmt(xMax) +
                              ", |y| <= " + fmt(yMax) + " m)");
  }
}

// ---------------------------------------------------------------------------------------------

CommandLine::CommandLine() : root_(std::make_unique<CLI::App>("nao-soccer: the NAO V6 robot program, its simulator, evaluations and benchmarks", "nao-soccer")),
                             options_(std::make_unique<Options>()) {
  root_->require_subcommand(1);
  declare();
}

CommandLine::~CommandLine() = default;

Command& CommandLine::leaf(CLI::App* parent, const std::string& name, const std::string& summary, CommonOptions& common) {
  CLI::App* app = parent->add_subcommand(name, summary);
  const std::string path = parent == root_.get() ? name : parent->get_name() + " " + name;
  commands_.push_back(std::make_unique<Command>(app, path, common));
  return *commands_.back();
}

CLI::App* CommandLine::group(const std::string& name, const std::string& summary) {
  CLI::App* app = root_->add_subcommand(name, summary);
  app->require_subcommand(1);
  return app;
}

std::vector<Command*> CommandLine::commands() const {
  std::vector<Command*> out;
  for (const auto& c : commands_) out.push_back(c.get());
  return out;
}

Command* CommandLine::command(const std::string& path) const {
  for (const auto& c : commands_)
    if (c->path() == path) return c.get();
  return nullptr;
}

std::string CommandLine::rootHelp() const { return root_->help(); }

namespace {

int fail(const std::string& command, const std::string& message, int code) {
  std::fprintf(stderr, "nao-soccer%s%s: %s\n", command.empty() ? "" : " ", command.c_str(), escapeControl(message).c_str());
  return code;
}

}  // namespace

int CommandLine::main(int argc, const char* const* argv) {
  if (argc < 2) {
    std::fputs(rootHelp().c_str(), stderr);
    return 2;
  }
  Command* command = nullptr;
  try {
    std::string help;
    command = parse(argc, argv, help);
    if (!command) {
      std::fputs(help.c_str(), stdout);
      return std::fflush(stdout) == 0 ? 0 : 1;
    }
  } catch (const Error& e) {
    return fail(parsedPath(), e.what(), 2);
  }
  if (!command->run) return fail(command->path(), "this program does not run it", 2);
  try {
    io::OutputTransaction outputs;
    outputs.discardOnSignals();
    const int code = command->run();
    if (std::fflush(stdout) != 0) throw RunFailure("stdout", "write failed");
    outputs.commit();
    return code;
  } catch (const RunFailure& e) {
    return fail(command->path(), e.what(), 1);
  } catch (const Error& e) {
    return fail(command->path(), e.what(), 2);
  } catch (const std::exception& e) {
    return fail(command->path(), std::string("internal error: ") + e.what(), 1);
  }
}

namespace {

// The deepest subcommand the parser entered, and its path ("eval perception").
const CLI::App* deepestSelected(const CLI::App* app, std::string& path) {
  for (const CLI::App* sub : app->get_subcommands({})) {
    if (sub->count() == 0 && !sub->parsed()) continue;
    path += (path.empty() ? "" : " ") + sub->get_name();
    return deepestSelected(sub, path);
  }
  return app;
}

std::string names(const CLI::App* app) {
  std::vector<std::string> n;
  for (const CLI::App* sub : app->get_subcommands({})) n.push_back(sub->get_name());
  return join(n, ", ");
}

// The first word after "name: " in CLI11's message, and the rest.
std::pair<std::string, std::string> splitName(const std::string& message) {
  const auto colon = message.find(": ");
  if (colon == std::string::npos) return {"", message};
  return {message.substr(0, colon), message.substr(colon + 2)};
}

}  // namespace

Command* CommandLine::parse(int argc, const char* const* argv, std::string& help) {
  try {
    root_->parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    help = root_->help();
    return nullptr;
  } catch (const CLI::ParseError& e) {
    std::string path;
    const CLI::App* at = deepestSelected(root_.get(), path);
    parsedPath_ = path;
    const bool isGroup = !at->get_subcommands({}).empty();
    const std::string where = path.empty() ? "nao-soccer" : path;
    const std::string message = e.what();
    const auto unknownIn = [&](std::string extra) {
      if (isGroup && (extra.empty() || extra[0] != '-'))
        throw Error(extra, std::string(path.empty() ? "unknown command" : "unknown target for '" + path + "'") +
                               " (one of " + names(at) + ")");
      if (!extra.empty() && extra[0] == '-' && extra != "-")
        throw Error(extra.substr(0, extra.find('=')),
                    "not an option of '" + where + "' (" + (path.empty() ? "nao-soccer" : "nao-soccer " + path) +
                        " --help lists them)");
      throw Error(extra, "unexpected argument for '" + where + "'");
    };
    if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
      // CLI11 lists the extras last first.
      std::string extra = splitName(message).second;
      extra = extra.substr(extra.rfind(' ') == std::string::npos ? 0 : extra.rfind(' ') + 1);
      unknownIn(extra);
    }
    if (dynamic_cast<const CLI::RequiredError*>(&e)) {
      if (isGroup) {
        if (const auto left = at->remaining(); !left.empty()) unknownIn(left.front());
        throw Error(where, "needs one of: " + names(at));
      }
      const auto [name, rest] = splitName(message);
      (void)rest;
      const std::string flag = message.substr(0, message.find(' '));
      throw Error(flag, "is required");
    }
    if (dynamic_cast<const CLI::ArgumentMismatch*>(&e)) {
      const auto [name, rest] = splitName(message);
      if (rest.find("At Most") != std::string::npos) throw Error(name, "given more than once");
      if (rest.find("missing") != std::string::npos || rest.find("At least") != std::string::npos)
        throw Error(name, "needs a value");
      if (const auto override = message.find(" was given a disallowed flag override"); override != std::string::npos)
        throw Error((message[0] == '-' ? "" : "--") + message.substr(0, override), "takes no value (it is a switch)");
      throw Error(name, "takes no value (it is a switch)");
    }
    if (dynamic_cast<const CLI::ExcludesError*>(&e)) {
      const auto space = message.find(" excludes ");
      if (space != std::string::npos)
        throw Error(message.substr(0, space), "cannot be combined with " + message.substr(space + 10));
    }
    if (dynamic_cast<const CLI::RequiresError*>(&e)) {
      const auto space = message.find(" requires ");
      if (space != std::string::npos) throw Error(message.substr(0, space), "needs " + message.substr(space + 10));
    }
    const auto [name, rest] = splitName(message);
    throw Error(name.empty() ? where : name, rest);
  }
  std::string path;
  deepestSelected(root_.get(), path);
  parsedPath_ = path;
  Command* c = command(path);
  if (!c) throw Error(path.empty() ? "nao-soccer" : path, "needs a command");
  c->finish();
  return c;
}

}  // namespace nao::cli
