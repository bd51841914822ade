#pragma once
// Where a camera's auto exposure looks: the NAO V6 camera (OV5640) meters the image's luminance
// in a 4 x 4 grid of equal cells, each weighted 0..15 (the sensor's AEC weight registers
// 0x5688..0x568F). The robot program chooses the weights from where the field is in the image
// (perception/ExposureWeighting.h); both backends apply them: the simulator's camera model meters
// with them, the NAO backend writes them to the camera (robot/nao/V4l2Camera.h).
#include <array>
#include <cstdint>

namespace nao {

struct ExposureWeights {
  static constexpr int kRows = 4, kCols = 4;
  static constexpr std::uint8_t kMax = 15;
  // Row-major, row 0 at the image's top. All equal (the camera's default): the plain mean.
  std::array<std::uint8_t, kRows * kCols> cell;

  ExposureWeights() { cell.fill(kMax); }
  std::uint8_t at(int row, int col) const { return cell[static_cast<std::size_t>(row * kCols + col)]; }
  bool uniform() const {
    for (std::uint8_t w : cell)
      if (w != cell[0]) return false;
    return true;
  }
  bool operator==(const ExposureWeights& o) const { return cell == o.cell; }
  bool operator!=(const ExposureWeights& o) const { return !(*this == o); }
};

}  // namespace nao
