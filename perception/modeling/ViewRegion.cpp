#include "perception/modeling/ViewRegion.h"

#include <algorithm>
#include <cmath>

namespace nao {

namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Andrew's monotone chain: the convex hull, counter-clockwise, without collinear points.
std::vector<Eigen::Vector2d> hull(std::vector<Eigen::Vector2d> p) {
  std::sort(p.begin(), p.end(), [](const auto& a, const auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  if (p.size() < 3) return {};
  std::vector<Eigen::Vector2d> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 1e-12) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 1e-12) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h.size() >= 3 ? h : std::vector<Eigen::Vector2d>{};
}

}  // namespace

std::vector<Eigen::Vector2d> groundView(const CameraMatrix& camera, double maxDistance, double margin) {
  const double w = camera.intrinsics.width, h = camera.intrinsics.height;
  const double x0 = margin * w, x1 = (1 - margin) * w, y0 = margin * h, y1 = (1 - margin) * h;
  if (!(maxDistance > 0) || !(x1 > x0) || !(y1 > y0)) return {};
  // An image entirely above the horizon sees no ground at all.
  bool seesGround = false;
  for (double py : {y0, y1})
    for (double px : {x0, x1}) seesGround = seesGround || camera.pixelToGround({px, py}).has_value();
  if (!seesGround) return {};
  const Eigen::Vector2d eye = camera.pose.translation().head<2>();
  std::vector<Eigen::Vector2d> points;
  // Along the image's border: where each pixel's ray meets the ground, or (at or above the
  // horizon, or farther) the point maxDistance away in the ray's direction. The ground under a
  // convex image region is convex, and so is its cut with the disc.
  constexpr int kPerEdge = 12;
  auto add = [&](double px, double py) {
    const Eigen::Vector2d pixel(px, py);
    const Eigen::Vector3d ray = camera.pixelRay(pixel);
    const Eigen::Vector2d along = ray.head<2>();
    const auto ground = camera.pixelToGround(pixel);
    if (ground && ground->norm() <= maxDistance) {
      points.push_back(*ground);
      return;
    }
    if (along.norm() < 1e-9) return;
    // Where the ray's direction crosses the circle of radius maxDistance about the robot.
    const Eigen::Vector2d u = along.normalized();
    const double b = eye.dot(u), c = eye.squaredNorm() - maxDistance * maxDistance;
    const double disc = b * b - c;
    if (disc < 0) return;
    const double t = -b + std::sqrt(disc);
    if (t > 0) points.push_back(eye + t * u);
  };
  for (int i = 0; i < kPerEdge; ++i) {
    const double f = static_cast<double>(i) / kPerEdge;
    add(x0 + f * (x1 - x0), y0);
    add(x1, y0 + f * (y1 - y0));
    add(x1 - f * (x1 - x0), y1);
    add(x0, y1 - f * (y1 - y0));
  }
  return hull(std::move(points));
}

double lengthInside(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const std::vector<Eigen::Vector2d>& polygon) {
  if (polygon.size() < 3) return 0;
  // Cyrus-Beck: the parameter interval of a + t (b - a) inside every edge's half-plane.
  const Eigen::Vector2d d = b - a;
  double t0 = 0, t1 = 1;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& p = polygon[i];
    const Eigen::Vector2d e = polygon[(i + 1) % polygon.size()] - p;
    // Inside: cross(e, x - p) >= 0.
    const double num = cross(e, a - p), den = cross(e, d);
    if (std::abs(den) < 1e-15) {
      if (num < 0) return 0;
      continue;
    }
    const double t = -num / den;
    if (den > 0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
    if (t0 >= t1) return 0;
  }
  return (t1 - t0) * d.norm();
}

}  // namespace nao
