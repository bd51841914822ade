#include "perception/ExposureWeighting.h"

#include <algorithm>
#include <cmath>

namespace nao {

ExposureWeights exposureWeights(const CameraMatrix& cm, const OwnBody& body, const ExposureWeightingParams& p) {
  ExposureWeights w;
  if (!p.enabled) return w;
  const double width = cm.intrinsics.width, height = cm.intrinsics.height;
  const int n = std::max(1, p.samplesPerCellSide);
  const Eigen::Vector2d foot = cm.pose.translation().head<2>();
  int total = 0;
  for (int row = 0; row < ExposureWeights::kRows; ++row)
    for (int col = 0; col < ExposureWeights::kCols; ++col) {
      int ground = 0;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const Eigen::Vector2d pixel((col + (j + 0.5) / n) * width / ExposureWeights::kCols,
                                      (row + (i + 0.5) / n) * height / ExposureWeights::kRows);
          const auto g = cm.pixelToGround(pixel);
          if (!g || (*g - foot).norm() > p.maxDistance || body.hides(cm, pixel)) continue;
          ++ground;
        }
      const auto weight = static_cast<std::uint8_t>(std::lround(ExposureWeights::kMax * ground / double(n * n)));
      w.cell[static_cast<std::size_t>(row * ExposureWeights::kCols + col)] = weight;
      total += weight;
    }
  if (total == 0) return ExposureWeights{};  // no near ground in view: the camera's default
  return w;
}

}  // namespace nao
