#include "sim/OracleCamera.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "sim/GroundTruth.h"
#include "sim/SceneBuilder.h"
#include "sim/World.h"

namespace nao::sim {

namespace {

constexpr double kMaxDistance = 9.0;  // m: farther than the error model detects anything
constexpr double kLineStep = 0.05;    // m between line samples

struct TrueCamera {
  Eigen::Isometry3d fieldToCamera;
  Eigen::Vector2d foot;
  double f = 0, width = 0, height = 0;

  std::optional<Eigen::Vector2d> pixel(const Eigen::Vector3d& pField) const {
    const Eigen::Vector3d p = fieldToCamera * pField;
    if (p.x() <= 1e-6) return std::nullopt;
    return Eigen::Vector2d(width / 2 - f * p.y() / p.x(), height / 2 - f * p.z() / p.x());
  }
  bool inImage(const Eigen::Vector2d& px) const {
    return px.x() >= 0 && px.y() >= 0 && px.x() < width && px.y() < height;
  }
  // The pixel of a ground point that is in the image and near enough.
  std::optional<Eigen::Vector2d> seen(const Eigen::Vector2d& p) const {
    if ((p - foot).norm() > kMaxDistance) return std::nullopt;
    const auto px = pixel(Eigen::Vector3d(p.x(), p.y(), 0.001));
    if (!px || !inImage(*px)) return std::nullopt;
    return px;
  }
};

}  // namespace

OracleView oracleView(const World& world, int robot, CameraId camera) {
  const Eigen::Isometry3d cam = world.cameraPose(robot, camera);
  const CameraResolution res = world.cameraResolution(camera);
  TrueCamera tc{cam.inverse(), cam.translation().head<2>(), (res.height / 2.0) / std::tan(world.cameraFovY() / 2),
                static_cast<double>(res.width), static_cast<double>(res.height)};
  const FieldModel& field = world.field();
  OracleView view;
  // Lines: the longest run of samples in view.
  for (const FieldLine& l : field.lines) {
    const double len = (l.to - l.from).norm();
    if (len < 1e-9) continue;
    const int n = std::max(2, static_cast<int>(len / kLineStep) + 1);
    // A sample counts with the paint's whole width in the image: where the border cuts the
    // paint lengthwise, no image shows the line's centre.
    const Eigen::Vector2d across = 0.5 * field.dims.lineWidth * Eigen::Vector2d(-(l.to - l.from).y(), (l.to - l.from).x()) / len;
    // Nor where a robot (the own feet and legs, before all) hides it.
    auto visible = [&](const Eigen::Vector2d& p) {
      return tc.seen(p) && tc.seen(p + across) && tc.seen(p - across) &&
             trulyVisible(world, robot, camera, Eigen::Vector3d(p.x(), p.y(), 0.001));
    };
    int bestStart = -1, bestEnd = -1, runStart = -1;
    for (int k = 0; k <= n; ++k) {
      const bool vis = k < n && visible(l.from + (l.to - l.from) * (static_cast<double>(k) / (n - 1)));
      if (vis && runStart < 0) runStart = k;
      if (!vis && runStart >= 0) {
        if (k - 1 - runStart > bestEnd - bestStart) bestStart = runStart, bestEnd = k - 1;
        runStart = -1;
      }
    }
    if (bestStart < 0 || bestEnd == bestStart) continue;
    const Eigen::Vector2d a = l.from + (l.to - l.from) * (static_cast<double>(bestStart) / (n - 1));
    const Eigen::Vector2d b = l.from + (l.to - l.from) * (static_cast<double>(bestEnd) / (n - 1));
    OracleView::Line line;
    line.imageFrom = *tc.seen(a);
    line.imageTo = *tc.seen(b);
    line.length = (b - a).norm();
    const Eigen::Vector2d u = (b - a) / line.length;
    const double t = std::clamp((tc.foot - a).dot(u), 0.0, line.length);
    line.distance = (a + t * u - tc.foot).norm();
    view.lines.push_back(line);
  }
  // The centre circle: at least half of it in view.
  constexpr int kCircleSamples = 72;
  int inView = 0;
  for (int k = 0; k < kCircleSamples; ++k) {
    const double a = 2 * M_PI * k / kCircleSamples;
    inView += tc.seen(field.centerCircleCenter + field.centerCircleRadius * Eigen::Vector2d(std::cos(a), std::sin(a))).has_value();
  }
  if (2 * inView >= kCircleSamples)
    if (const auto px = tc.pixel(Eigen::Vector3d(field.centerCircleCenter.x(), field.centerCircleCenter.y(), 0.001)))
      view.circleCentre = OracleView::Spot{*px, (field.centerCircleCenter - tc.foot).norm()};
  // A penalty cross with its four arm ends in the image.
  for (const Eigen::Vector2d& c : field.penaltyCrosses) {
    bool whole = true;
    for (const Eigen::Vector2d& d : {Eigen::Vector2d(0.05, 0), Eigen::Vector2d(-0.05, 0), Eigen::Vector2d(0, 0.05),
                                    Eigen::Vector2d(0, -0.05)})
      whole = whole && tc.seen(c + d);
    if (whole) view.penaltyMark = OracleView::Spot{*tc.seen(c), (c - tc.foot).norm()};
  }
  // Balls: in front of the camera, some of the disc in the image, not hidden.
  for (int b = 0; b < world.ballCount(); ++b) {
    const Eigen::Vector3d centre = world.ballPosition(b);
    const Eigen::Vector3d inCamera = tc.fieldToCamera * centre;
    const auto px = tc.pixel(centre);
    if (!px || inCamera.x() <= kBallRadius) continue;
    const double distance = (centre.head<2>() - tc.foot).norm();
    if (distance > kMaxDistance) continue;
    OracleView::Ball ball;
    ball.image = *px;
    ball.radiusPx = tc.f * kBallRadius / inCamera.x();
    ball.distance = distance;
    ball.inImage = discInImage(ball.image, ball.radiusPx, res.width, res.height);
    if (ball.inImage <= 0 || !ballVisible(world, robot, camera, b, kMaxDistance)) continue;
    view.balls.push_back(ball);
  }
  return view;
}

CameraImage oracleImage(const World& world, int robot, CameraId camera) {
  const CameraResolution res = world.cameraResolution(camera);
  CameraImage image;
  image.camera = camera;
  image.width = res.width;
  image.height = res.height;
  image.oracle = std::make_shared<const OracleView>(oracleView(world, robot, camera));
  return image;
}

}  // namespace nao::sim
