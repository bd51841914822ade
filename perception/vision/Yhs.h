#pragma once
// YUV -> YHS2 (B-Human's luminance/hue/saturation derived from YUV, not from RGB):
//   h = atan2(v - 128, u - 128) scaled to 0..255 per full turn (wrapping),
//   s = 2 * hypot(u - 128, v - 128), clamped to 255 (chroma; twice so that it spans 0..255),
//   y = the luminance unchanged.
// Saturated greens have hue about 160 (-130 deg), yellow 121 (170 deg), cyan 205 (-71 deg).
// Table-driven: one 64 KiB (h, s) table over (u, v), built once on first use.
#include <cstdint>
#include <cstdlib>

#include "perception/vision/VisionTypes.h"

namespace nao {

struct HueSat {
  std::uint8_t h = 0, s = 0;
};

// The (h, s) of every (u, v): index (u << 8) | v.
const HueSat* yhsTable();

inline HueSat hueSat(std::uint8_t u, std::uint8_t v) { return yhsTable()[(static_cast<int>(u) << 8) | v]; }
inline Yhs toYhs(std::uint8_t y, std::uint8_t u, std::uint8_t v) {
  const HueSat hs = hueSat(u, v);
  return {y, hs.h, hs.s};
}
// Means (rounded to the table's resolution).
Yhs toYhs(double y, double u, double v);

// Circular distance of two hues, 0..128.
inline int hueDistance(int a, int b) {
  const int d = std::abs(a - b) & 255;
  return d > 128 ? 256 - d : d;
}
// Signed circular offset b - a in -128..127.
inline int hueOffset(int a, int b) { return static_cast<std::int8_t>(static_cast<std::uint8_t>(b - a)); }

}  // namespace nao
