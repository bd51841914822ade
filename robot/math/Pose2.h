#pragma once
// A 2-D pose or displacement (x, y in m, theta in rad); also a walk speed (m/s, rad/s).
#include <cmath>
#include <numbers>

#include <Eigen/Core>

namespace nao {

struct Pose2 {
  double x = 0, y = 0, theta = 0;

  Pose2() = default;
  Pose2(double x_, double y_, double theta_) : x(x_), y(y_), theta(theta_) {}

  // This pose followed by `o` expressed in this pose's frame.
  Pose2 operator*(const Pose2& o) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * o.x - s * o.y, y + s * o.x + c * o.y, wrap(theta + o.theta)};
  }
  Eigen::Vector2d operator*(const Eigen::Vector2d& p) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * p.x() - s * p.y(), y + s * p.x() + c * p.y()};
  }
  Pose2 inverse() const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {-(c * x + s * y), s * x - c * y, -theta};
  }
  Eigen::Vector2d translation() const { return {x, y}; }
  static double wrap(double a) {
    a = std::remainder(a, 2 * std::numbers::pi);
    return a <= -std::numbers::pi ? a + 2 * std::numbers::pi : a;
  }
};

}  // namespace nao
