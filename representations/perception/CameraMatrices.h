#pragma once
// Both cameras' calibrated matrices (robot frame) of this cycle (CameraMatrixProvider).
#include <array>

#include "perception/CameraModel.h"
#include "robot/CameraImage.h"

namespace nao {

struct CameraMatrices {
  std::array<CameraMatrix, kNumCameras> matrix;
};

}  // namespace nao
