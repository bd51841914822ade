#pragma once
// Runs the nao-soccer binary (NAO_BINARY) with `args` in a shell; stdout and stderr together,
// or apart. With a time limit, a run still going after it is killed (exit 137): a hang fails
// the test.
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace nao::test {

struct CommandResult {
  int code = -1;
  std::string out;  // stdout + stderr
};

inline CommandResult runCommand(const std::string& args, int timeoutSeconds = 0) {
  const std::string limit = timeoutSeconds > 0 ? "timeout -s KILL " + std::to_string(timeoutSeconds) + " " : "";
  const std::string cmd = limit + std::string(NAO_BINARY) + " " + args + " 2>&1";
  CommandResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), buf.size(), p)) r.out += buf.data();
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

struct SplitResult {
  int code = -1;
  std::string out, err;
};

// stdout and stderr apart; `env` (e.g. "VAR=value") goes before the command.
inline SplitResult runCommandSplit(const std::string& args, int timeoutSeconds, const std::string& env = "") {
  const auto errFile = std::filesystem::temp_directory_path() /
                       ("nao_run_stderr_" + std::to_string(::getpid()) + ".txt");
  const std::string cmd = env + " timeout -s KILL " + std::to_string(timeoutSeconds) + " " + std::string(NAO_BINARY) +
                          " " + args + " 2>" + errFile.string();
  SplitResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  while (std::size_t n = fread(buf.data(), 1, buf.size(), p)) r.out.append(buf.data(), n);
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream f(errFile);
  r.err.assign(std::istreambuf_iterator<char>(f), {});
  std::error_code ec;
  std::filesystem::remove(errFile, ec);
  return r;
}

}  // namespace nao::test
