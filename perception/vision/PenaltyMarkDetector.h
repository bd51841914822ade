#pragma once
// The penalty cross: a white blob on a vertical scan line as tall as the cross is there,
// as wide as the cross along its image row, surrounded by field colour on two rings around it
// on the ground (at most one sample of each not field, at least three quarters of each in
// view), and away from every detected line (which also rules out the centre mark on the
// halfway line).
#include <array>
#include <optional>
#include <vector>

#include "perception/CameraModel.h"
#include "perception/vision/ColourTests.h"
#include "perception/vision/VisionTypes.h"

namespace nao::vision {

struct PenaltyMarkParams {
  double size = 0.1;          // m, the cross's extent (FieldDimensions::penaltyCrossSize)
  double minSizeRatio = 0.4, maxSizeRatio = 1.9;
  std::array<double, 2> ringRadii{0.17, 0.3};  // m, where the surrounding field is tested
  double minRingInView = 0.75;  // of each ring's samples
  int maxRingMisses = 1;        // samples on a ring that are not field (noise, a shadow's edge)
  double lineClearance = 0.25;  // m from every detected line
  double maxDistance = 5;     // m
};

// The mark's position in the robot frame; `imagePos` (optional) receives its pixel. Nothing
// inside the ball's disc is a mark.
std::optional<Eigen::Vector2d> detectPenaltyMark(const CameraImage& image, const ScanLineRegions& regions,
                                                 const FieldReference& field,
                                                 const std::vector<LinesPercept::Line>& lines,
                                                 const ObstaclesPercept& obstacles, const CameraMatrix& cm,
                                                 const PenaltyMarkParams& params = {},
                                                 Eigen::Vector2d* imagePos = nullptr, const BallPercept* ball = nullptr);

}  // namespace nao::vision
