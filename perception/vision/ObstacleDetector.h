#pragma once
// Other robots, as far as the line and ball detectors need them: on each vertical scan line,
// a long run of non-field regions (white or other) that ends below the field boundary and is
// as tall as a robot's lower part would be at its foot point, or that reaches up to the
// boundary (or the image top) and is much taller than a field line is wide there; runs on
// neighbouring lines join into one obstacle when together they are as wide as a robot's leg
// at least (and not wider than a few robots). The box extends upwards by a robot's height.
#include "perception/CameraModel.h"
#include "perception/vision/VisionTypes.h"

namespace nao {

// regions: best those of the whole image (computeScanLineRegions without a boundary), so that
// a robot near the boundary, whose body rises above it, is seen whole; regions cut at the
// boundary work too. segmentField passes the whole image's.
ObstaclesPercept detectObstacles(const CameraImage& image, const ScanLineRegions& regions, const FieldBoundary& boundary,
                                 const CameraMatrix& cm);

}  // namespace nao
