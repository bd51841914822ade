#pragma once
// The one image a cognition run processes (RobotProgram runs cognition once per image): a
// cognition pipeline input.
#include "robot/CameraImage.h"

namespace nao {

struct CurrentImage {
  CameraImage image;
};

}  // namespace nao
