#pragma once
// Representations the robot program's modules exchange (plain structs, docs/../design.md).
#include <array>
#include <optional>

#include "controllers/FallDetector.h"
#include "perception/CameraModel.h"
#include "robot/CameraImage.h"
#include "robot/JointRequest.h"
#include "robot/SensorData.h"

namespace nao {

// The images that arrived this cycle (none most cycles: the cameras run at 30 Hz).
struct CameraImages {
  std::array<std::optional<CameraImage>, kNumCameras> latest;
};

// The calibrated camera matrices of this cycle (robot frame).
struct CameraMatrices {
  std::array<CameraMatrix, kNumCameras> matrix;
};

// Torso orientation and height from IMU and legs.
struct TorsoState {
  Eigen::Isometry3d robotToTorso = Eigen::Isometry3d::Identity();
};

}  // namespace nao
