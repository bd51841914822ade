#pragma once
// Sensor noise, measured on the image itself, and a box blur for images where it is high. At
// the camera's limits (dim light: longest exposure, gain 4) the noise breaks the scan-line
// regions into pieces and hides small balls; the vision then reads a blurred copy (measured in
// docs/vision/README.md, "Noise"). Images with ordinary noise are left exactly as they are.
#include "robot/CameraImage.h"

namespace nao {

struct DenoiseParams {
  bool enabled = true;
  // Blur only above this luma noise (the sweep's presets measure 2-3, `noisy` 6-7, `dim` 11-12).
  double minNoise = 9.0;
  int radius = 1;  // the box is (2 radius + 1) pixels square
  int sampleStep = 4;  // the noise is measured on every sampleStep-th pixel and row
};

// The luma's noise standard deviation: the median absolute difference of horizontal
// neighbours / (0.6745 sqrt 2), robust against the edges of lines and objects (which are few
// among the samples). 0 for an invalid image.
double lumaNoise(const CameraImage& image, int sampleStep = 4);

// out = image with Y, U and V each averaged over a box (2 radius + 1) pixels square (U and V on
// their own half-width grid, radius / 2 pairs across, at least 1); the box shrinks at the
// border. radius <= 0 copies.
void boxBlur(const CameraImage& image, int radius, CameraImage& out);

template <class V>
void describe(V& v, DenoiseParams& p) {
  v("enabled", p.enabled);
  v("minNoise", p.minNoise, 0.0, 255.0);
  v("radius", p.radius, 1, 8);
  v("sampleStep", p.sampleStep, 1, 64);
}

}  // namespace nao
