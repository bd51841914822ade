#pragma once
// The image the noise-sensitive vision reads (ImageDenoiser, perception/vision/Denoise.h): a
// blurred copy when this image's noise is high, else the camera image itself.
#include "robot/CameraImage.h"

namespace nao {

struct DenoisedImage {
  double noise = 0;  // the camera image's luma noise (standard deviation, in luma steps)
  int radius = 0;    // of the box blur; 0: not blurred (`blurred` keeps only its buffer, unused)
  CameraImage blurred;

  const CameraImage& image(const CameraImage& raw) const { return radius > 0 ? blurred : raw; }
};

}  // namespace nao
