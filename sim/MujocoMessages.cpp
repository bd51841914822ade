#include "sim/MujocoMessages.h"

#include <mujoco/mujoco.h>

#include <cstdio>
#include <mutex>
#include <string>

#include "robot/Error.h"

namespace nao::sim {

namespace {

std::string oneLine(const char* msg) {
  std::string out;
  for (const char* c = msg; c && *c; ++c) out += (*c == '\n' || *c == '\r') ? ' ' : *c;
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

void warning(const char* msg) { std::fprintf(stderr, "nao-soccer: MuJoCo warning: %s\n", oneLine(msg).c_str()); }

// MuJoCo expects the handler not to return. Its C frames carry unwind tables on x86-64, so an
// exception leaves them as a longjmp would (MuJoCo's Python bindings do the same).
void error(const char* msg) { throw RunFailure("MuJoCo", oneLine(msg)); }

}  // namespace

void routeMujocoMessages() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_warning = warning;
    mju_user_error = error;
  });
}

}  // namespace nao::sim
