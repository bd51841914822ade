#pragma once
// Does the robot program's camera model agree with the renderer? For random robot poses and
// head angles (both cameras, with and without injected offsets that the model is told), the
// edges of the painted field lines are located in the rendered image with sub-pixel accuracy
// and compared with the camera model's projection of the same edges; line corners (where two
// paint edges meet) are measured as the intersection of the two fitted image edges.
// The model gets only what the robot program gets (joint angles, IMU angles) plus the injected
// offsets; the truth is the rendered image itself.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "robot/CameraImage.h"

namespace nao::sim {

struct AgreementOptions {
  int poses = 50;            // per camera and per offset setting
  std::uint64_t seed = 1;
  double maxOffsetDeg = 3;   // injected offsets are uniform in +-this (when enabled)
  std::string fieldFile;     // empty: config/field_dimensions.json
  std::string imagesDir;     // non-empty: annotated PNG per trial (green: predicted, red: measured)
  bool modelIgnoresOffsets = false;  // for testing the test: the model is not told the offsets
};

struct CornerMeasurement {
  int trial = 0;
  CameraId camera = CameraId::Top;
  bool offsets = false;
  Eigen::Vector2d predicted, measured;
  double errorPx = 0;
};

struct AgreementResult {
  int trials = 0;
  int trialsWithCorners = 0;
  std::vector<CornerMeasurement> corners;
  std::vector<double> edgeErrorsPx;  // signed, along the image normal of each edge sample
  double cornerRmsPx = 0, cornerMaxPx = 0, edgeRmsPx = 0, edgeMedianAbsPx = 0;
};

AgreementResult measureCameraAgreement(const AgreementOptions& options);

}  // namespace nao::sim
