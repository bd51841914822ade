// libFuzzer target: the declared command line (apps/cli/). The input is split at NUL bytes into
// argv. Every argv must be parsed into a command, answered with help, or refused with
// nao::Error (exit 2 in the program); any other exception, a crash or a sanitizer report is a
// finding. Parsing only: no command runs.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "apps/cli/CommandLine.h"
#include "robot/Error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> words{"nao-soccer"};
  std::string word;
  for (std::size_t i = 0; i < size; ++i) {
    if (data[i] == 0) {
      words.push_back(word);
      word.clear();
    } else {
      word += static_cast<char>(data[i]);
    }
  }
  if (!word.empty()) words.push_back(word);
  if (words.size() > 64) return 0;
  std::vector<const char*> argv;
  for (const auto& w : words) argv.push_back(w.c_str());
  nao::cli::CommandLine cl;
  std::string help;
  try {
    nao::cli::Command* c = cl.parse(static_cast<int>(argv.size()), argv.data(), help);
    // Parsed: the flags it reports as given were all declared by that command.
    if (c)
      for (const auto& flag : c->common().given) {
        bool declared = false;
        for (const auto& s : c->specs()) declared = declared || s.flag == flag;
        if (!declared && flag != "--help") std::abort();
      }
  } catch (const nao::Error& e) {
    if (std::string(e.what()).empty()) std::abort();
  }
  return 0;
}
