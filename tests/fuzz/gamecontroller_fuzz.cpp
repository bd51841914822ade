// libFuzzer target: the GameController packet parsers and the receiver's state update
// (robot/nao/GameController). Valid packets must survive a serialize/parse round trip.
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>

#include "robot/Error.h"
#include "robot/nao/GameController.h"

namespace {

nao::GameController& receiver() {
  // Bound once on loopback with a free port; it never sends (no GameController address is a
  // real sender: handlePacket gets none).
  static auto gc = [] {
    nao::GameController::Config c;
    c.team = 12;
    c.player = 3;
    c.port = 0;
    c.bindAddress = "127.0.0.1";
    return std::make_unique<nao::GameController>(c, [](const std::string&) {});
  }();
  return *gc;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const nao::gc::GameControlData d = nao::gc::parseGameControlData(data, size);
    const auto bytes = nao::gc::serialize(d);
    if (bytes.size() != size || std::memcmp(bytes.data(), data, size) != 0) std::abort();
  } catch (const nao::Error&) {
  }
  try {
    const nao::gc::ReturnData r = nao::gc::parseReturnData(data, size);
    const auto bytes = nao::gc::serialize(r);
    if (bytes.size() != size || std::memcmp(bytes.data(), data, size) != 0) std::abort();
  } catch (const nao::Error&) {
  }
  static double now = 0;
  now += 0.012;
  receiver().handlePacket(data, size, now);
  (void)nao::chestColour(receiver().state());
  return 0;
}
