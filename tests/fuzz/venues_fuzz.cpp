// libFuzzer target: the venues reader (sim/VenueLook.h), which every --venue reads from
// config/venues.json (a file a team edits for its own halls). Any input must either load or throw
// nao::Error with a one-line message; anything else (a crash, another exception, a sanitizer
// report) is a finding, and so is a loaded look outside the ranges the reader promises.
#include <cstdint>
#include <cstdlib>
#include <string>

#include <nlohmann/json.hpp>

#include "robot/Error.h"
#include "sim/VenueLook.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto looks =
        nao::sim::parseVenueLooks(std::string(reinterpret_cast<const char*>(data), size), "venues.json");
    if (looks.empty()) std::abort();
    for (const auto& v : looks) {
      if (v.name.empty() || !v.turf.allFinite() || !v.wall.allFinite() || !v.floorLines.allFinite()) std::abort();
      if (!(v.turf.y() > v.turf.x()) && !v.plain()) std::abort();
      if (v.people < 0 || v.people > 24 || v.boards < 0 || v.tables < 0 || v.windows < 0 || v.doors < 0) std::abort();
      if (!(v.lineWear >= 0 && v.lineWear <= 0.3) || !(v.stripeWidth >= 0 && v.stripeWidth <= 5)) std::abort();
      (void)nao::sim::toJson(v).dump();
    }
  } catch (const nao::Error& e) {
    if (std::string(e.what()).find('\n') != std::string::npos) std::abort();
  }
  return 0;
}
