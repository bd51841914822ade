#include "perception/vision/Yhs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

namespace nao {
namespace {

HueSat compute(double u, double v) {
  const double du = u - 128, dv = v - 128;
  const double turn = std::atan2(dv, du) / (2 * M_PI);  // -0.5 .. 0.5
  const int h = static_cast<int>(std::lround(turn * 256)) & 255;
  const double s = std::min(255.0, 2 * std::hypot(du, dv));
  return {static_cast<std::uint8_t>(h), static_cast<std::uint8_t>(std::lround(s))};
}

}  // namespace

const HueSat* yhsTable() {
  // A function-local static: built once, thread-safe.
  static const std::unique_ptr<std::array<HueSat, 65536>> table = [] {
    auto t = std::make_unique<std::array<HueSat, 65536>>();
    for (int u = 0; u < 256; ++u)
      for (int v = 0; v < 256; ++v) (*t)[(u << 8) | v] = compute(u, v);
    return t;
  }();
  return table->data();
}

Yhs toYhs(double y, double u, double v) {
  auto byte = [](double a) { return static_cast<std::uint8_t>(std::clamp(static_cast<int>(a + 0.5), 0, 255)); };
  return toYhs(byte(y), byte(u), byte(v));
}

}  // namespace nao
