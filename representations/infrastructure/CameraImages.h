#pragma once
// The images that arrived this cycle (none most cycles: the cameras run at 30 Hz). A pipeline
// input: the robot program fills it from the backend.
#include <array>
#include <optional>

#include "robot/CameraImage.h"

namespace nao {

struct CameraImages {
  std::array<std::optional<CameraImage>, kNumCameras> latest;
};

}  // namespace nao
