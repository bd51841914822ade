#include "perception/vision/VisionTypes.h"

#include <algorithm>

namespace nao {

double FieldBoundary::yAt(double x) const {
  if (!valid || points.empty()) return 0;
  if (points.size() == 1) return points.front().y();
  // The segment containing x; beyond the ends the end segments are extended.
  std::size_t i = 1;
  while (i + 1 < points.size() && points[i].x() < x) ++i;
  const Eigen::Vector2d& a = points[i - 1];
  const Eigen::Vector2d& b = points[i];
  const double dx = b.x() - a.x();
  if (dx <= 1e-9) return std::min(a.y(), b.y());
  return a.y() + (x - a.x()) / dx * (b.y() - a.y());
}

bool ObstaclesPercept::contains(double x, double y) const {
  return std::any_of(obstacles.begin(), obstacles.end(), [&](const Obstacle& o) {
    return x >= o.left && x < o.right && y >= o.top && y < o.bottom;
  });
}

}  // namespace nao
