// libFuzzer target: LoLA's sensor packet parser and the stream framing (robot/nao/LolaPacket).
// Any input must either decode or throw nao::Error; anything else (a crash, another
// exception, a sanitizer report, a huge allocation) is a finding.
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "robot/Error.h"
#include "robot/nao/LolaPacket.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const nao::lola::SensorPacket p = nao::lola::decodeSensorPacket(data, size);
    // A decoded packet holds finite numbers only.
    for (double v : p.position)
      if (!std::isfinite(v)) std::abort();
    nao::SensorFrame frame;
    nao::lola::toSensorFrame(p, frame);
  } catch (const nao::Error&) {
  }
  try {
    const std::size_t n = nao::lola::objectLength(data, size);
    if (n > size) std::abort();
  } catch (const nao::Error&) {
  }
  return 0;
}
