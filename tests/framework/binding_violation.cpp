// Compiled by ctest with -fsyntax-only (tests/framework.cmake): without a VIOLATION it must
// compile; each VIOLATION must fail with the framework's own message. This is the proof that
// a module cannot read or write what it did not declare.
#include "robot/Module.h"

namespace {

struct Input {
  int v = 0;
};
struct Output {
  int v = 0;
};
struct Other {
  int v = 0;
};

#if VIOLATION == 3
// Writes its own input (what CameraMatrixProvider once did with the program's configuration).
class Bad : public nao::Module<Bad, nao::Requires<Input, Output>, nao::Provides<Output>> {
  void update() override {}
};
#else
class Bad : public nao::Module<Bad, nao::Requires<Input>, nao::Provides<Output>> {
  void update() override {
#if VIOLATION == 1
    out<Output>().v = in<Other>().v;  // reads what it did not require
#elif VIOLATION == 2
    out<Input>().v = 1;  // writes what it only requires
#else
    out<Output>().v = in<Input>().v;
#endif
  }
};
#endif

}  // namespace

int main() {
  Bad bad;
  nao::Blackboard board;
  board.write<Input>();
  bad.execute(board);
}
