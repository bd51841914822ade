#pragma once
// Which part of an image the auto exposure should meter (robot/ExposureWeights.h): the ground
// within a few metres, not the robot's own body, not what lies above the horizon. A camera that
// meters its whole image exposes for the hall: a lit wall or ceiling over a dim field leaves the
// field black (measured in docs/vision/README.md, "Metering the field"); a bottom camera looking
// at its own white chest darkens the carpet. Each cell's weight is the share of its area that
// sees the near ground, in 0..15; an image with no such cell keeps the camera's default.
#include "perception/CameraModel.h"
#include "perception/OwnBody.h"
#include "robot/ExposureWeights.h"

namespace nao {

struct ExposureWeightingParams {
  bool enabled = true;  // false: the camera's default (its whole image, evenly)
  double maxDistance = 6.0;  // m from the camera's foot: farther ground is metered no more
  int samplesPerCellSide = 6;  // rays per cell: this many squared
  // AutoExposureWeighting keeps a camera's weights until the new ones differ by this much
  // (the sum over the cells of the weights' differences): on a NAO each change is a USB
  // control transfer, and a scanning head would change them with nearly every image.
  int minChange = 12;
};

// body: may be empty (nothing hidden).
ExposureWeights exposureWeights(const CameraMatrix& cm, const OwnBody& body, const ExposureWeightingParams& params);

template <class V>
void describe(V& v, ExposureWeightingParams& p) {
  v("enabled", p.enabled);
  v("maxDistance", p.maxDistance, 0.5, 100.0);
  v("samplesPerCellSide", p.samplesPerCellSide, 1, 32);
  v("minChange", p.minChange, 0, 240);
}

}  // namespace nao
