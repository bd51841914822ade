// perception/modeling/ViewRegion: the ground a camera image surely shows, against geometry
// worked out here (a camera at a known height and pitch), and segment clipping.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "perception/modeling/ViewRegion.h"

namespace nao {
namespace {

using Vec2 = Eigen::Vector2d;
constexpr double kDeg = std::numbers::pi / 180;

CameraMatrix camera(double height, double pitch, double yaw = 0) {
  CameraMatrix m;
  m.intrinsics = CameraIntrinsics::nominal(CameraId::Top);
  m.pose = Eigen::Translation3d(0, 0, height) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
           Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY());
  return m;
}

bool inside(const Vec2& p, const std::vector<Vec2>& polygon) {
  // A tiny segment about p lies inside exactly when p does.
  return lengthInside(p - Vec2(1e-4, 0), p + Vec2(1e-4, 0), polygon) > 1.9e-4;
}

TEST(ViewRegion, TheGroundUnderACameraLookingDown) {
  const double h = 0.5, pitch = 30 * kDeg;
  const CameraMatrix m = camera(h, pitch);
  const auto view = groundView(m, 3.0, 0.1);
  ASSERT_GE(view.size(), 3u);
  // The optical axis meets the ground h / tan(pitch) ahead.
  EXPECT_TRUE(inside(Vec2(h / std::tan(pitch), 0), view));
  EXPECT_FALSE(inside(Vec2(-0.5, 0), view));  // behind
  EXPECT_FALSE(inside(Vec2(3.5, 0), view));   // beyond the cut
  EXPECT_FALSE(inside(Vec2(1, 2), view));     // beside the field of view
  for (std::size_t i = 0; i < view.size(); ++i) {
    // Convex and counter-clockwise, no farther than the cut.
    const Vec2 a = view[i], b = view[(i + 1) % view.size()], c = view[(i + 2) % view.size()];
    EXPECT_GT((b - a).x() * (c - b).y() - (b - a).y() * (c - b).x(), 0) << i;
    EXPECT_LE(a.norm(), 3.0 + 1e-9);
    // Each corner is on the image inside the margin (or on the cut).
    const auto px = m.projectGround(a);
    ASSERT_TRUE(px.has_value());
    if (a.norm() < 3.0 - 1e-6) {
      EXPECT_GE(px->x(), 0.1 * 640 - 1e-6);
      EXPECT_LE(px->x(), 0.9 * 640 + 1e-6);
      EXPECT_GE(px->y(), 0.1 * 480 - 1e-6);
      EXPECT_LE(px->y(), 0.9 * 480 + 1e-6);
    }
  }
  // A line across the view 1 m ahead: as long as the view is wide there (the image less its
  // margins: 0.8 of the horizontal field of view at the ray's depth).
  const double across = lengthInside(Vec2(1, -5), Vec2(1, 5), view);
  const double depth = std::hypot(1.0, h) * std::cos(std::atan2(h, 1.0) - pitch);  // along the optical axis
  const double halfWidth = 0.8 * depth * (m.intrinsics.width / 2.0) / m.intrinsics.fx;
  EXPECT_NEAR(across, 2 * halfWidth, 0.03);
  // Turned by the yaw, the view turns along.
  const auto turned = groundView(camera(h, pitch, 90 * kDeg), 3.0, 0.1);
  EXPECT_TRUE(inside(Vec2(0, h / std::tan(pitch)), turned));
  EXPECT_FALSE(inside(Vec2(h / std::tan(pitch), 0), turned));
}

TEST(ViewRegion, ACameraAboveTheHorizonSeesNoGround) {
  EXPECT_TRUE(groundView(camera(0.5, -60 * kDeg), 3.0, 0.1).empty());
  EXPECT_TRUE(groundView(camera(0.5, 30 * kDeg), 0.0, 0.1).empty());
  // Level: the lower half sees the ground, cut at the distance.
  const auto level = groundView(camera(0.5, 0), 3.0, 0.1);
  ASSERT_FALSE(level.empty());
  EXPECT_TRUE(inside(Vec2(2.5, 0), level));
}

TEST(ViewRegion, LengthInsideAConvexPolygon) {
  const std::vector<Vec2> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_NEAR(lengthInside({-1, 0.5}, {2, 0.5}, square), 1.0, 1e-12);
  EXPECT_NEAR(lengthInside({0.2, 0.2}, {0.5, 0.6}, square), 0.5, 1e-12);
  EXPECT_NEAR(lengthInside({-1, -1}, {2, 2}, square), std::sqrt(2.0), 1e-12);
  EXPECT_EQ(lengthInside({2, 0}, {3, 1}, square), 0);
  EXPECT_EQ(lengthInside({-1, 0.5}, {2, 0.5}, {}), 0);
  EXPECT_EQ(lengthInside({-1, 0.5}, {2, 0.5}, {{0, 0}, {1, 0}}), 0);
}

}  // namespace
}  // namespace nao
