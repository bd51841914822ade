#pragma once
// Where each camera's auto exposure meters (AutoExposureWeighting): cognition chooses a camera's
// weights from its latest image; the robot program hands them to the backend when they change.
#include <array>

#include "robot/CameraImage.h"
#include "robot/ExposureWeights.h"

namespace nao {

struct AutoExposureWeights {
  std::array<ExposureWeights, kNumCameras> camera;  // default: the whole image, evenly
};

}  // namespace nao
