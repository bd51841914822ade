#pragma once
// The field boundary of one image (classical, no learning): on each vertical scan line, the
// topmost point below which field regions dominate (the maximum of a running score from the
// image bottom upwards: + field length, - other length, white neutral); then a RANSAC fit of
// the upper envelope of these points by one line or two lines meeting in a corner (the
// carpet is convex, so its image boundary is y = max(l1(x), l2(x))). Points below the fit
// (robots, the ball, shadows hiding the edge) cost nothing; points above it (field colour
// beyond the carpet) count against it, so the fit hugs the true edge from below the
// outliers. When no fit explains enough of the points (a field broken up by sun and shadow),
// the boundary is level through the upper tenth of them. Works alike on simulated and real
// images: no thresholds but geometry.
#include "perception/CameraModel.h"
#include "perception/vision/VisionTypes.h"

namespace nao {

// regions: computed without a boundary (the whole grid). The result spans x = 0 .. width;
// invalid when no field is seen. When the field reaches the top of the scanned area the
// boundary lies there (the image top, or the horizon).
FieldBoundary detectFieldBoundary(const CameraImage& image, const ScanLineRegions& regions, const CameraMatrix& cm);

}  // namespace nao
