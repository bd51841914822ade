#pragma once
// Drawing the first half of the vision onto an RGB image (CV_8UC3 in RGB order, the size of
// the camera image): scan-line regions coloured by class (field green, white red as in the
// paper's figures, other blue), the field boundary (yellow) and obstacles (magenta boxes).
#include <opencv2/core.hpp>

#include "perception/vision/VisionTypes.h"

namespace nao {

void drawScanLineRegions(cv::Mat& rgb, const ScanLineRegions& regions);
void drawFieldBoundary(cv::Mat& rgb, const FieldBoundary& boundary);
void drawObstacles(cv::Mat& rgb, const ObstaclesPercept& obstacles);

}  // namespace nao
