#pragma once
// The penalty mark in one image (PenaltyMarkPerceptor).
#include <optional>

#include <Eigen/Core>

namespace nao {

struct PenaltyMarkPercept {
  std::optional<Eigen::Vector2d> position;         // robot frame (m), when found
  Eigen::Vector2d image = Eigen::Vector2d::Zero();  // its pixel, when found
};

}  // namespace nao
