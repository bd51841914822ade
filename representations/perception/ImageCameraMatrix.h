#pragma once
// The current image's camera matrix at its exposure time (ExposureCameraMatrixProvider): what
// every percept of that image is projected with.
#include "perception/CameraModel.h"
#include "robot/CameraImage.h"

namespace nao {

struct ImageCameraMatrix {
  CameraId camera = CameraId::Top;
  double timestamp = 0;  // s, the image's exposure time
  CameraMatrix matrix;
  bool valid = false;  // false until a motion cycle has been seen
};

}  // namespace nao
