#pragma once
// An annotated picture of what the vision found in one image: scan-line regions coloured by
// class, the field boundary, obstacles, the line spots and lines, the centre circle,
// intersections (L, T, X), the penalty mark, the goal box side and the ball.
#include <opencv2/core.hpp>

#include "perception/CameraModel.h"
#include "perception/vision/VisionPipeline.h"

namespace nao {

// rgb: the camera image as CV_8UC3 in RGB order; returns a copy with the drawing on it,
// scaled by `scale` (nearest neighbour) so that thin marks stay readable.
cv::Mat annotateVision(const cv::Mat& rgb, const VisionResult& result, const CameraMatrix& cm, int scale = 1);

}  // namespace nao
