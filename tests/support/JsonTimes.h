#pragma once
// A run's JSON without its wall-clock figures (wall_s, extract_ms, solve_s, at any depth): what
// two runs of the same seed must agree on.
#include <nlohmann/json.hpp>

namespace nao::test {

inline nlohmann::json withoutTimes(nlohmann::json j) {
  if (j.is_object()) {
    for (const char* key : {"wall_s", "extract_ms", "solve_s"}) j.erase(key);
    for (auto& [key, value] : j.items()) value = withoutTimes(value);
  } else if (j.is_array()) {
    for (auto& value : j) value = withoutTimes(value);
  }
  return j;
}

}  // namespace nao::test
