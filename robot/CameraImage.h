#pragma once
// A camera image exactly as the NAO delivers it: YUV422 (YUYV: Y0 U Y1 V per pixel pair),
// upright, row 0 at the top. Pixel (i, j) covers [i, i+1) x [j, j+1); its centre is (i+0.5, j+0.5).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

namespace nao {

struct OracleView;  // robot/OracleView.h

enum class CameraId : int { Top = 0, Bottom = 1 };
inline constexpr int kNumCameras = 2;
inline const char* cameraName(CameraId c) { return c == CameraId::Top ? "top" : "bottom"; }

struct CameraImage {
  CameraId camera = CameraId::Top;
  int width = 0;
  int height = 0;
  double timestamp = 0;            // s, backend clock, when the exposure was taken
  std::vector<std::uint8_t> yuyv;  // width * height * 2 bytes
  // The simulator's fast percept mode only: what the camera truly shows instead of pixels.
  std::shared_ptr<const OracleView> oracle;

  bool valid() const {
    return width > 0 && height > 0 && width % 2 == 0 &&
           yuyv.size() == static_cast<std::size_t>(width) * height * 2;
  }
  std::uint8_t y(int x, int yy) const { return yuyv[(static_cast<std::size_t>(yy) * width + x) * 2]; }
  std::uint8_t u(int x, int yy) const { return yuyv[(static_cast<std::size_t>(yy) * width + (x & ~1)) * 2 + 1]; }
  std::uint8_t v(int x, int yy) const { return yuyv[(static_cast<std::size_t>(yy) * width + (x & ~1)) * 2 + 3]; }
};

// std::clamp(std::lround(v), 0L, 255L) without lround's library call (per byte of an image it
// was a third of a conversion's time); the same value for every v.
inline std::uint8_t roundToByte(double v) {
  if (!(v > 0)) return 0;
  if (v >= 255) return 255;
  int r = static_cast<int>(v + 0.5);
  if (r - 0.5 > v) --r;  // v + 0.5 rounded up to the next integer in its last bit
  return static_cast<std::uint8_t>(r);
}

// One YUYV pixel pair from two RGB pixels (BT.601 full range, U and V from the pair's mean):
// how the simulator's renders and decoded image files become what a NAO camera delivers.
inline void yuyvPairFromRgb(const std::uint8_t* rgb, std::uint8_t* yuyv) {
  const auto byte = roundToByte;
  const double r0 = rgb[0], g0 = rgb[1], b0 = rgb[2], r1 = rgb[3], g1 = rgb[4], b1 = rgb[5];
  const double ra = (r0 + r1) / 2, ga = (g0 + g1) / 2, ba = (b0 + b1) / 2;
  yuyv[0] = byte(0.299 * r0 + 0.587 * g0 + 0.114 * b0);
  yuyv[1] = byte(128 - 0.168736 * ra - 0.331264 * ga + 0.5 * ba);
  yuyv[2] = byte(0.299 * r1 + 0.587 * g1 + 0.114 * b1);
  yuyv[3] = byte(128 + 0.5 * ra - 0.418688 * ga - 0.081312 * ba);
}

}  // namespace nao
