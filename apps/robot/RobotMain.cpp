// nao-soccer-robot: the robot-only executable deployed to a NAO V6 (robot/deploy/deploy.sh). It
// holds the robot program and the NAO backend and nothing of the simulator. Its command line is
// `nao-soccer run --backend nao`'s, declared once in apps/cli/ and parsed the same way:
//   nao-soccer-robot [OPTIONS]                  = nao-soccer run --backend nao [OPTIONS]
//   nao-soccer-robot run --backend nao [OPTIONS] (the same; what the start script passes)
// The process ends as nao-soccer's does (apps/main.cpp): 0 success, 1 a failed run, 2 bad usage
// or input, each failure one line; files a run writes appear only when it ends without error.
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include <opencv2/core/utils/logger.hpp>

#include "apps/Commands.h"
#include "apps/cli/CommandLine.h"
#include "apps/cli/Options.h"
#include "robot/Error.h"
#include "robot/OutputFiles.h"

namespace {

using nao::cli::CommandLine;

constexpr const char* kProgram = "nao-soccer-robot";

int fail(const std::string& command, const std::string& message, int code) {
  std::fprintf(stderr, "%s%s%s: %s\n", kProgram, command.empty() ? "" : " ", command.c_str(),
               nao::cli::escapeControl(message).c_str());
  return code;
}

// Only `run --backend nao` is in this executable; every other command stays in nao-soccer.
void bind(CommandLine& cl) {
  for (nao::cli::Command* c : cl.commands()) {
    c->run = []() -> int {
      throw nao::Error("", "not in " + std::string(kProgram) + ", which runs only `run --backend nao` (use nao-soccer)");
    };
  }
  const nao::cli::RunOptions& run = cl.options().run;
  cl.command("run")->run = [&run]() -> int {
    if (run.backend != "nao")
      throw nao::Error("--backend", run.backend + ": " + kProgram + " has only the nao backend (the simulator is in nao-soccer)");
    return nao::cli::runNao(run);
  };
}

}  // namespace

int main(int argc, char** argv) {
  // OpenCV's own log lines would break the one-line errors; failures reach us as exceptions.
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  CommandLine cl;
  bind(cl);
  // Without a command word the options are `run --backend nao`'s.
  std::vector<const char*> args(argv, argv + argc);
  if (argc < 2 || std::strcmp(argv[1], "run") != 0) {
    bool backend = false;
    for (int i = 1; i < argc; ++i)
      backend |= std::strcmp(argv[i], "--backend") == 0 || std::strncmp(argv[i], "--backend=", 10) == 0;
    args.insert(args.begin() + 1, "run");
    if (!backend) args.insert(args.begin() + 2, {"--backend", "nao"});
  }
  nao::cli::Command* command = nullptr;
  try {
    std::string help;
    command = cl.parse(static_cast<int>(args.size()), args.data(), help);
    if (!command) {
      std::fputs(help.c_str(), stdout);
      return std::fflush(stdout) == 0 ? 0 : 1;
    }
  } catch (const nao::Error& e) {
    return fail(cl.parsedPath(), e.what(), 2);
  }
  try {
    nao::io::OutputTransaction outputs;
    const int code = command->run();
    if (std::fflush(stdout) != 0) throw nao::RunFailure("stdout", "write failed");
    outputs.commit();
    return code;
  } catch (const nao::RunFailure& e) {
    return fail(command->path(), e.what(), 1);
  } catch (const nao::Error& e) {
    return fail(command->path(), e.what(), 2);
  } catch (const std::exception& e) {
    return fail(command->path(), std::string("internal error: ") + e.what(), 1);
  }
}
