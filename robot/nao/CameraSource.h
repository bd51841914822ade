#pragma once
// Where the NAO backend's images come from: the V4L2 cameras (V4l2Camera) or image files
// (FileCamera, --cameras files:DIR). Both hand frames over the same way: grab() is
// non-blocking and only copies out a frame that is already there.
#include "robot/CameraImage.h"
#include "robot/ExposureWeights.h"

namespace nao {

class CameraSource {
 public:
  virtual ~CameraSource() = default;
  // True when a new frame arrived since the last call; `image` then holds the newest one,
  // timestamp = its capture time in CLOCK_MONOTONIC seconds. now: CLOCK_MONOTONIC seconds.
  virtual bool grab(CameraImage& image, double now) = 0;
  // Where the camera's auto exposure meters from now on; a source without one ignores it.
  virtual void setExposureWeights(const ExposureWeights& /*weights*/) {}
};

}  // namespace nao
