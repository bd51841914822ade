#pragma once
// Runs the nao-soccer binary (NAO_BINARY) with `args` in a shell; stdout and stderr together.
// With a time limit, a run still going after it is killed (exit 137): a hang fails the test.
#include <sys/wait.h>

#include <array>
#include <cstdio>
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

}  // namespace nao::test
