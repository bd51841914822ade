// libFuzzer target: the module parameter loader (robot/Parameters.h) on the motion engine's,
// head control's, the fall detector's and the oracle vision's Params (lists of numbers, text). Any input must either load or throw
// nao::Error with a one-line message; anything else (a crash, another exception, a sanitizer
// report, a loaded value that is not finite) is a finding.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "controllers/modules/FallDetector.h"
#include "controllers/modules/HeadControl.h"
#include "controllers/modules/MotionEngineParams.h"
#include "controllers/modules/OracleVision.h"
#include "robot/Error.h"
#include "robot/Parameters.h"

namespace {

// Every number a loaded struct holds must be finite (the writer walks the same fields).
void checkFinite(const nlohmann::ordered_json& j) {
  for (const auto& v : j) {
    if (v.is_object() || v.is_array()) checkFinite(v);
    else if (v.is_number_float() && !std::isfinite(v.get<double>())) std::abort();
  }
}

template <class P>
void load(const std::string& text) {
  P p;
  try {
    nao::applyParamsText(text, "fuzz.json", p);
    checkFinite(nao::paramsToJson(p));
  } catch (const nao::Error& e) {
    if (std::string(e.what()).find('\n') != std::string::npos) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  load<nao::MotionEngine::Params>(text);
  load<nao::HeadControl::Params>(text);
  load<nao::FallDetector::Params>(text);
  load<nao::modules::OracleVision::Params>(text);
  return 0;
}
