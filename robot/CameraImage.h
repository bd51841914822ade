#pragma once
// A camera image exactly as the NAO delivers it: YUV422 (YUYV: Y0 U Y1 V per pixel pair),
// upright, row 0 at the top. Pixel (i, j) covers [i, i+1) x [j, j+1); its centre is (i+0.5, j+0.5).
#include <cstdint>
#include <vector>

namespace nao {

enum class CameraId : int { Top = 0, Bottom = 1 };
inline constexpr int kNumCameras = 2;
inline const char* cameraName(CameraId c) { return c == CameraId::Top ? "top" : "bottom"; }

struct CameraImage {
  CameraId camera = CameraId::Top;
  int width = 0;
  int height = 0;
  double timestamp = 0;            // s, backend clock, when the exposure was taken
  std::vector<std::uint8_t> yuyv;  // width * height * 2 bytes

  bool valid() const {
    return width > 0 && height > 0 && width % 2 == 0 &&
           yuyv.size() == static_cast<std::size_t>(width) * height * 2;
  }
  std::uint8_t y(int x, int yy) const { return yuyv[(static_cast<std::size_t>(yy) * width + x) * 2]; }
  std::uint8_t u(int x, int yy) const { return yuyv[(static_cast<std::size_t>(yy) * width + (x & ~1)) * 2 + 1]; }
  std::uint8_t v(int x, int yy) const { return yuyv[(static_cast<std::size_t>(yy) * width + (x & ~1)) * 2 + 3]; }
};

}  // namespace nao
