#include "perception/modeling/ModelingTypes.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

namespace nao {

double RobotPose::sigmaTranslation() const {
  const Eigen::Matrix2d xy = covariance.topLeftCorner<2, 2>();
  if (!xy.allFinite()) return std::numeric_limits<double>::infinity();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(0.5 * (xy + xy.transpose()));
  return std::sqrt(std::max(0.0, es.eigenvalues().maxCoeff()));
}

double RobotPose::sigmaRotation() const {
  const double v = covariance(2, 2);
  return std::isfinite(v) ? std::sqrt(std::max(0.0, v)) : std::numeric_limits<double>::infinity();
}

std::optional<Pose2> odometryDelta(const Pose2& from, const Pose2& to) {
  auto finite = [](const Pose2& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta); };
  if (!finite(from) || !finite(to)) return std::nullopt;
  return from.inverse() * to;
}

}  // namespace nao
