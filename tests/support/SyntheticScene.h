#pragma once
// Synthetic camera images with exact truth: grass below the horizon (a grey wall above it),
// 5 cm white paint where a predicate on the ground (robot frame) says, and spheres (balls,
// shaded obstacles) ray-traced through the camera model. Used by ball_test and the vision
// module tests.
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "perception/CameraModel.h"
#include "sim/ImageIO.h"

namespace nao::test {

inline constexpr double kSyntheticBallRadius = 0.05;

// A sphere lying in the scene (robot frame); its reflectance as a function of the surface
// normal (robot frame).
struct Sphere {
  Eigen::Vector3d centre;
  double radius = kSyntheticBallRadius;
  std::function<double(const Eigen::Vector3d&)> albedo;
};

// A soccer ball's reflectance: 12 black patches (centred on an icosahedron's vertices,
// together about a third of the surface) on white, turned by `rotation`.
inline std::function<double(const Eigen::Vector3d&)> soccerBall(const Eigen::Matrix3d& rotation) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<Eigen::Vector3d> centres;
  for (double a : {-1.0, 1.0})
    for (double b : {-g, g}) {
      centres.push_back(rotation * Eigen::Vector3d(0, a, b).normalized());
      centres.push_back(rotation * Eigen::Vector3d(a, b, 0).normalized());
      centres.push_back(rotation * Eigen::Vector3d(b, 0, a).normalized());
    }
  return [centres](const Eigen::Vector3d& n) {
    for (const auto& c : centres)
      if (n.dot(c) > std::cos(0.33)) return 0.06;
    return 0.92;
  };
}

inline std::function<double(const Eigen::Vector3d&)> plain(double albedo) {
  return [albedo](const Eigen::Vector3d&) { return albedo; };
}

struct Light {
  double gain = 1.0;
  cv::Vec3d tint = {1, 1, 1};  // RGB factors (warm light: blue and green weaker)
  double noise = 2.0;
};

// Grass below the horizon (a grey wall above it), 5 cm white paint where `paint` says,
// spheres lit by a light from above and behind the camera plus ambient light. 2x2
// supersampled, then the light's gain and tint and sensor noise.
// carpet (optional): where the carpet ends; the ground beyond is the grey wall's colour.
inline CameraImage syntheticImage(const CameraMatrix& cm, const std::vector<Sphere>& spheres,
                                  const std::function<bool(const Eigen::Vector2d&)>& paint, const Light& light = {},
                                  CameraId camera = CameraId::Top, double blurPx = 0,
                                  const std::function<bool(const Eigen::Vector2d&)>& carpet = {}) {
  const int w = cm.intrinsics.width, h = cm.intrinsics.height;
  const Eigen::Vector3d origin = cm.pose.translation();
  const Eigen::Vector3d toLight = Eigen::Vector3d(-0.4, 0.3, 1).normalized();
  cv::Mat rgb(h, w, CV_64FC3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      cv::Vec3d sum(0, 0, 0);
      for (double dy : {0.25, 0.75})
        for (double dx : {0.25, 0.75}) {
          const Eigen::Vector2d px(x + dx, y + dy);
          const Eigen::Vector3d ray = cm.pixelRay(px).normalized();
          double best = 1e9;
          cv::Vec3d c(110, 110, 110);
          for (const Sphere& s : spheres) {
            const Eigen::Vector3d oc = origin - s.centre;
            const double b = oc.dot(ray), disc = b * b - (oc.squaredNorm() - s.radius * s.radius);
            if (disc < 0) continue;
            const double t = -b - std::sqrt(disc);
            if (t <= 0 || t >= best) continue;
            best = t;
            const Eigen::Vector3d n = (origin + t * ray - s.centre).normalized();
            const double shade = s.albedo(n) * (0.35 + 0.65 * std::max(0.0, n.dot(toLight)));
            c = cv::Vec3d(255, 255, 250) * shade;
          }
          if (best > 1e8) {
            if (const auto g = cm.pixelToGround(px); g && (!carpet || carpet(*g)))
              c = paint(*g) ? cv::Vec3d(235, 235, 230) : cv::Vec3d(40, 140, 45);
          }
          sum += c;
        }
      rgb.at<cv::Vec3d>(y, x) = sum / 4;
    }
  if (blurPx > 0) {  // motion blur along the image x axis, and the lens out of focus
    const int k = 2 * static_cast<int>(blurPx / 2) + 1;
    cv::blur(rgb, rgb, cv::Size(k, 1));
    cv::GaussianBlur(rgb, rgb, cv::Size(0, 0), 0.3 * blurPx);
  }
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0, light.noise);
  cv::Mat out(h, w, CV_8UC3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < 3; ++k)
        out.at<cv::Vec3b>(y, x)[k] =
            cv::saturate_cast<std::uint8_t>(rgb.at<cv::Vec3d>(y, x)[k] * light.gain * light.tint[k] + n(rng));
  return sim::cameraImageFromRgb(out, camera);
}

inline const std::function<bool(const Eigen::Vector2d&)> kNoPaint = [](const Eigen::Vector2d&) { return false; };

}  // namespace nao::test
