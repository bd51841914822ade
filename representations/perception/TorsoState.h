#pragma once
// Torso orientation and height from the IMU and the legs (TorsoMatrixProvider provides it).
#include <Eigen/Geometry>

namespace nao {

struct TorsoState {
  Eigen::Isometry3d robotToTorso = Eigen::Isometry3d::Identity();
};

}  // namespace nao
