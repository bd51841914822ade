#pragma once
// Sizes of what is painted and played with (m), from the field file: the camera pipeline's
// input besides the image and its camera matrix (perception/vision/CameraPipeline.h).
namespace nao {

struct FieldDimensions;

struct VisionGeometry {
  double lineWidth = 0.05;
  double circleRadius = 0.75;  // to the line centre
  double penaltyCrossSize = 0.1;
  double ballRadius = 0.05;
  static VisionGeometry from(const FieldDimensions& d);  // perception/vision/CameraPipeline.cpp
};

}  // namespace nao
