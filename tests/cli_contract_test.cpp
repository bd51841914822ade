// The command line's contract, walked from the declarations themselves (apps/cli/): for every
// command and every option it declares, a malformed value, an out-of-range value, a missing or
// wrong file each give exit 2 and exactly one line that names the option, before any work is
// done and without leaving a file behind. Also: every command's --help lists its options with
// their units and ranges, and an option a command does not declare is refused.
//
// Each bad line goes first through CommandLine::main in this process, the command bodies replaced
// by a marker (a process start costs a quarter second, and there are over a thousand lines). A
// line the parser refuses is judged there; a line that reaches a body (refused there, e.g. a
// file's contents) runs in the real binary. Every command's unknown option and stray argument
// always run in the binary, so its wiring of main is checked too.
#include <gtest/gtest.h>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "apps/cli/CommandLine.h"
#include "support/RunCommand.h"

namespace {

namespace fs = std::filesystem;
using nao::cli::Command;
using nao::cli::CommandLine;
using nao::cli::OptionSpec;

struct BadCase {
  std::string value;  // as the shell gets it (already quoted where needed)
  std::string what;
};

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::string joinValues(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ",") + x;
  return s;
}

// A folder per case: the inputs it needs, and afterwards proof that nothing was left in it.
struct Sandbox {
  fs::path dir;
  explicit Sandbox(const std::string& name) : dir(fs::path(::testing::TempDir()) / ("cli_contract_" + name)) {
    fs::remove_all(dir);
    fs::create_directories(dir / "in");
    std::ofstream(dir / "in" / "file.txt") << "not what any option wants\n";
    fs::copy_file(fs::path(NAO_SOURCE_DIR) / "docs/images/sim_top_calibration_view.png", dir / "in" / "image.png");
  }
  std::string in(const std::string& name) const { return (dir / "in" / name).string(); }
  std::string out(const std::string& name) const { return (dir / name).string(); }
  // Everything but in/: what the run left behind.
  std::vector<std::string> leftovers() const {
    std::vector<std::string> left;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().filename() != "in") left.push_back(e.path().filename().string());
    return left;
  }
};

std::vector<BadCase> badValues(const OptionSpec& s, const Sandbox& box) {
  using K = OptionSpec::Kind;
  std::vector<BadCase> cases;
  switch (s.kind) {
    case K::Switch:
      cases.push_back({"=1", "a value for a switch"});
      break;
    case K::Number:
      cases = {{"abc", "not a number"},
               {"nan", "NaN"},
               {"1e400", "infinite"},
               {"''", "empty"},
               {num(s.hi + (s.hi - s.lo) + 1), "above the range"},
               {num(s.lo - (s.hi - s.lo) - 1), "below the range"}};
      break;
    case K::Count:
      cases = {{"abc", "not a number"},      {"1.5", "not whole"},
               {"''", "empty"},              {num(s.hi + 1), "above the range"},
               {num(s.lo - 1), "below the range"}, {"99999999999999999999", "overflow"}};
      break;
    case K::Choice:
      cases = {{"bogus", "not a choice"}, {"''", "empty"}};
      if (!s.choices.empty()) {
        std::string upper = s.choices[0];
        for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        cases.push_back({upper, "a choice in the wrong case"});
      }
      break;
    case K::Numbers: {
      const std::size_t n = s.elements.size();
      std::vector<std::string> ok;
      for (const auto& e : s.elements) ok.push_back(num((e.lo + e.hi) / 2));
      if (s.elements[0].name == "WIDTH") {  // --size WxH
        cases = {{"640x", "no height"}, {"641x480", "odd width"}, {"99999x480", "too wide"}, {"axb", "not numbers"}};
        break;
      }
      cases.push_back({joinValues(std::vector<std::string>(ok.begin(), ok.end() - 1)), "too few numbers"});
      auto more = ok;
      more.push_back("0");
      cases.push_back({joinValues(more), "too many numbers"});
      for (std::size_t i = 0; i < n; ++i) {
        auto bad = ok;
        bad[i] = num(s.elements[i].hi + 1);
        cases.push_back({joinValues(bad), s.elements[i].name + " above its range"});
        bad[i] = "x";
        cases.push_back({joinValues(bad), s.elements[i].name + " not a number"});
        bad[i] = "nan";
        cases.push_back({joinValues(bad), s.elements[i].name + " NaN"});
      }
      if (!s.choices.empty()) cases.push_back({"bogus", "neither a choice nor numbers"});
      break;
    }
    case K::InputFile:
      cases = {{box.out("missing.json"), "a missing file"},
               {box.dir.string(), "a folder"},
               {"''", "an empty name"},
               {"/dev/zero", "a device that never ends"}};
      break;
    case K::OutputFile:
      cases = {{box.out("no/such/folder/x.out"), "a missing folder"},
               {box.dir.string(), "a folder"},
               {"''", "an empty name"}};
      break;
    case K::OutputFolder:
      cases = {{box.in("file.txt") + "/sub", "a file in the way"}, {"''", "an empty name"}};
      break;
    case K::Text:
      cases = {{"''", "empty"}};
      break;
  }
  return cases;
}

// The options a command needs to start (its required ones), with valid values.
std::string requiredArgs(const Command& c, const Sandbox& box, const std::string& except) {
  std::string args;
  for (const CLI::Option* o : c.app()->get_options()) {
    if (!o->get_required() || o->get_name() == except) continue;
    if (o->get_positional()) args += " " + box.in("image.png");
    else if (o->get_type_name() == "DIR") args += " " + o->get_name() + " " + box.in("");  // an input folder
    else args += " " + o->get_name() + " " + box.out("required.out");
  }
  return args;
}

int lineCount(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

struct Tally {
  int cases = 0, failures = 0;
};

// The shell words of `args` ('' is an empty word; no other quoting is used here).
std::vector<std::string> words(const std::string& args) {
  std::vector<std::string> w;
  std::size_t i = 0;
  while (i < args.size()) {
    if (args[i] == ' ') {
      ++i;
      continue;
    }
    const std::size_t end = std::min(args.find(' ', i), args.size());
    std::string word = args.substr(i, end - i);
    if (word.size() >= 2 && word.front() == '\'' && word.back() == '\'') word = word.substr(1, word.size() - 2);
    w.push_back(word);
    i = end;
  }
  return w;
}

constexpr int kReachedBody = 99;

// `args` through CommandLine::main here, stdout and stderr together; exit kReachedBody when the
// parser accepted the line and a command body would have run.
nao::test::CommandResult parseHere(const std::string& args) {
  CommandLine cl;
  for (Command* c : cl.commands()) c->run = [] { return kReachedBody; };
  std::vector<std::string> w = words(args);
  w.insert(w.begin(), "nao-soccer");
  std::vector<const char*> argv;
  for (const auto& x : w) argv.push_back(x.c_str());
  argv.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  FILE* tmp = std::tmpfile();
  const int savedOut = dup(1), savedErr = dup(2);
  dup2(fileno(tmp), 1);
  dup2(fileno(tmp), 2);
  nao::test::CommandResult r;
  r.code = cl.main(static_cast<int>(w.size()), argv.data());
  std::fflush(stdout);
  std::fflush(stderr);
  dup2(savedOut, 1);
  dup2(savedErr, 2);
  close(savedOut);
  close(savedErr);
  std::rewind(tmp);
  char buf[4096];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, tmp)) r.out.append(buf, n);
  std::fclose(tmp);
  return r;
}

enum class Via { ParserFirst, Binary };

// Runs one bad command line and checks the contract; `mustName` must appear in the one line.
void expectRefused(const std::string& args, const std::string& mustName, const Sandbox& box, const std::string& what,
                   Tally& tally, Via via = Via::ParserFirst) {
  ++tally.cases;
  nao::test::CommandResult r;
  if (via == Via::ParserFirst) r = parseHere(args);
  if (via == Via::Binary || r.code == kReachedBody) r = nao::test::runCommand(args, 60);
  const auto left = box.leftovers();
  const bool ok = r.code == 2 && lineCount(r.out) == 1 && r.out.rfind("nao-soccer", 0) == 0 &&
                  r.out.find(mustName) != std::string::npos && left.empty();
  if (!ok) {
    ++tally.failures;
    ADD_FAILURE() << "nao-soccer " << args << " (" << what << "): exit " << r.code << ", "
                  << (left.empty() ? std::string() : "left " + left.front() + ", ") << "said:\n"
                  << r.out;
  }
  for (const auto& l : left) fs::remove_all(box.dir / l);
}

TEST(CliContract, EveryDeclaredOptionRefusesBadValues) {
  CommandLine cl;
  Tally tally;
  for (const Command* c : cl.commands()) {
    const Sandbox box(c->path().substr(0, c->path().find(' ')) + "_" + std::to_string(tally.cases));
    for (const OptionSpec& s : c->specs()) {
      const std::string base = c->path() + requiredArgs(*c, box, s.flag);
      for (const BadCase& bad : badValues(s, box)) {
        const std::string args = s.positional ? base + " " + bad.value
                                 : s.kind == OptionSpec::Kind::Switch ? base + " " + s.flag + bad.value
                                                                      : base + " " + s.flag + " " + bad.value;
        expectRefused(args, s.flag, box, bad.what, tally);
      }
    }
    // An option nobody declared, and a stray argument.
    const Sandbox box2(c->path().substr(0, c->path().find(' ')) + "_extra");
    expectRefused(c->path() + requiredArgs(*c, box2, "") + " --frobnicate 3", "--frobnicate", box2, "unknown option", tally,
                  Via::Binary);
    expectRefused(c->path() + requiredArgs(*c, box2, "") + " stray stray2", "stray", box2, "stray argument", tally, Via::Binary);
  }
  std::printf("cli contract: %d bad command lines over %zu commands, %d not refused as promised\n", tally.cases,
              cl.commands().size(), tally.failures);
  EXPECT_GT(tally.cases, 600);
}

// Files that exist but hold garbage: each refused with one line naming the file, before work.
TEST(CliContract, EveryInputFileRefusesBadContents) {
  CommandLine cl;
  Tally tally;
  const std::vector<std::pair<std::string, std::string>> contents = {
      {"empty", ""},
      {"truncated", "{\"field\": {\"length\": 9.0, "},
      {"garbage", std::string("\x89PNG\x0d\x0a\x1a\x0a\xff\xfe<not>{json}\x01\x02", 20)},
      {"text", "hello\n"}};
  for (const Command* c : cl.commands())
    for (const OptionSpec& s : c->specs()) {
      if (s.kind != OptionSpec::Kind::InputFile) continue;
      const Sandbox box("contents");
      for (const auto& [name, bytes] : contents) {
        const std::string file = box.in(name + ".dat");
        std::ofstream(file, std::ios::binary) << bytes;
        std::string prefix = c->path();
        // Options of the NAO backend need it chosen; that run stops at the file, before LoLA.
        if (c->path() == "run" && s.flag.rfind("--camera", 0) == 0) prefix += " --backend nao";
        const std::string args = prefix + requiredArgs(*c, box, s.flag) + (s.positional ? " " : " " + s.flag + " ") + file;
        expectRefused(args, file, box, name + " file", tally);
      }
    }
  std::printf("cli contract: %d files with bad contents, %d not refused as promised\n", tally.cases, tally.failures);
  EXPECT_GT(tally.cases, 40);
}

// A new user's sweep, written without looking at the declarations: the same absurd inputs to
// every command. Each must be refused (exit 2, one line naming the flag) whether the command
// takes the option (then the value is out of bounds) or not (then the option is unknown to it):
// never accepted, never ignored.
TEST(CliContract, AbsurdInputsToEveryCommand) {
  const Sandbox box("absurd");
  const std::vector<std::pair<std::string, std::string>> absurd = {
      {"--seed", "-1"},
      {"--seed", "18446744073709551615"},
      {"--seed", "1.5"},
      {"--trials", "99999999999"},
      {"--trials", "0"},
      {"--trials", "-3"},
      {"--seconds", "1e30"},
      {"--seconds", "1e-300"},
      {"--seconds", "-5"},
      {"--seconds", "nan"},
      {"--repeats", "100000"},
      {"--frames", "0"},
      {"--json", "''"},
      {"--json", box.out("missing/out.json")},
      {"--json", box.dir.string()},
      {"--field", box.dir.string()},
      {"--field", box.in("file.txt") + "x"},
      {"--pose", "1e30,0,0"},
      {"--pose", "0,0,1e30"},
      {"--pose", "9,0,0"},
      {"--head", "1e30,0"},
      {"--head", "0,-90"},
      {"--ball", "100,0"},
      {"--camera", "left"},
      {"--lighting", "intensity=1e30"},
      {"--miscalibration", "45,0,0,0,0,0"},
      {"--max-offset", "90"},
      {"--vx", "1e9"},
      {"--scale", "1000"},
      {"--images", box.in("file.txt")},
      {"--out", box.dir.string()},
      {"--backend", "robot"},
      {"--team", "999"},
      {"--gc-port", "70000"},
      {"--randomize=yes", ""},
      {"--solver", "newton"},
  };
  CommandLine cl;
  Tally tally;
  for (const Command* c : cl.commands())
    for (const auto& [flag, value] : absurd) {
      const std::string args = c->path() + requiredArgs(*c, box, flag) + " " + flag + (value.empty() ? "" : " " + value);
      expectRefused(args, flag.substr(0, flag.find('=')), box, "absurd", tally);
    }
  std::printf("cli contract: %d absurd command lines over %zu commands, %d not refused as promised\n", tally.cases,
              cl.commands().size(), tally.failures);
}

TEST(CliContract, HelpListsEveryOptionWithUnitsAndRanges) {
  CommandLine cl;
  for (const Command* c : cl.commands()) {
    const auto r = nao::test::runCommand(c->path() + " --help");
    EXPECT_EQ(r.code, 0) << c->path();
    for (const OptionSpec& s : c->specs()) {
      EXPECT_NE(r.out.find(s.flag), std::string::npos) << c->path() << " --help lacks " << s.flag;
      if (s.kind == OptionSpec::Kind::Number) {
        const std::string range = num(s.lo) + ".." + num(s.hi) + " " + s.unit;
        EXPECT_NE(r.out.find(range), std::string::npos) << c->path() << " --help lacks " << s.flag << "'s " << range;
      }
      if (s.kind == OptionSpec::Kind::Count) {
        const std::string range = num(s.lo) + ".." + num(s.hi);
        EXPECT_NE(r.out.find(range), std::string::npos) << c->path() << " --help lacks " << s.flag << "'s " << range;
      }
      for (const auto& e : s.elements)
        EXPECT_NE(r.out.find(e.name), std::string::npos) << c->path() << " --help lacks " << s.flag << "'s " << e.name;
    }
  }
}

TEST(CliContract, OptionsGivenTwiceAreRefused) {
  CommandLine cl;
  Tally tally;
  for (const Command* c : cl.commands())
    for (const OptionSpec& s : c->specs()) {
      if (s.kind != OptionSpec::Kind::Count || s.positional) continue;
      const Sandbox box("twice");
      const std::string v = num(s.lo);
      expectRefused(c->path() + requiredArgs(*c, box, "") + " " + s.flag + " " + v + " " + s.flag + " " + v, s.flag,
                    box, "given twice", tally);
    }
  std::printf("cli contract: %d command lines with an option given twice, %d not refused as promised\n", tally.cases,
              tally.failures);
  EXPECT_GT(tally.cases, 10);
}

}  // namespace
