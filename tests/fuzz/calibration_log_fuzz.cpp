// libFuzzer target: the calibration log reader (perception/calibration/CalibrationLog.h). Any
// input must either parse or throw nao::Error; anything else (a crash, another exception, a
// sanitizer report, a huge allocation) is a finding, and so is a parsed image of the wrong size.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "perception/calibration/CalibrationLog.h"
#include "robot/Error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const nao::calibration::CalibrationLog log =
        nao::calibration::parseCalibrationLog(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz");
    for (const auto& r : log.records)
      if (!r.image.valid()) std::abort();
  } catch (const nao::Error&) {
  }
  return 0;
}
