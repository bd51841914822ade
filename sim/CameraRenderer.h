#pragma once
// Off-screen rendering of a MuJoCo camera through OSMesa or EGL (sim/GlContext.h: --gl; no
// display either way).
// The image is an exact pinhole projection: the viewport is exactly width x height, the
// MuJoCo camera's fovy is the vertical field of view, square pixels, principal point at the
// centre, no lens effects. Each renderer owns one context and makes it current in every call,
// so several renderers may coexist (single-threaded use only).
#include <memory>
#include <opencv2/core.hpp>
#include <random>
#include <string>

#include "robot/CameraImage.h"
#include "sim/Lighting.h"

struct mjModel_;
struct mjData_;

namespace nao::sim {

// Writes `lighting` into the model's sun light (named "sun") and headlight, and the sun's
// direction into d's light frames (so no mj_forward is needed before rendering).
void applyLighting(mjModel_* m, mjData_* d, const Lighting& lighting);

// Adds zero-mean sensor noise to a YUYV image: std. dev. sigma on Y, sigma/2 on U and V,
// drawn from rng (approximately Gaussian: a sum of four uniforms, bounded at 3.5 sigma).
void addSensorNoise(CameraImage& image, double sigma, std::mt19937_64& rng);

// Where a camera image's time went (ms): the scene's update from the state, the draw calls,
// reading the pixels back (it waits for the drawing to finish), the YUYV conversion, the sensor
// noise. renderRgb sets the first three.
struct RenderStages {
  double scene = 0, draw = 0, read = 0, convert = 0, noise = 0;
};

class CameraRenderer {
 public:
  // Creates the context and its offscreen buffer (m->vis.global.offwidth x offheight) and
  // uploads m's meshes and textures. Throws nao::Error("renderer", ...) when no context can be
  // made.
  explicit CameraRenderer(const mjModel_* m);
  ~CameraRenderer();
  CameraRenderer(const CameraRenderer&) = delete;
  CameraRenderer& operator=(const CameraRenderer&) = delete;

  // The image of MuJoCo camera mjCameraId with d's current state: CV_8UC3 in RGB order (not
  // OpenCV's BGR), row 0 at the top. Applies `lighting` to m first (shadows per lighting).
  // A model other than the last one rebuilds the GPU context. Throws nao::Error("renderer", ...)
  // for a bad camera id or a size beyond the model's offscreen buffer.
  cv::Mat renderRgb(mjModel_* m, mjData_* d, int mjCameraId, int width, int height, const Lighting& lighting);

  // renderRgb converted to YUYV (BT.601 full range, U/V averaged over each pixel pair) with
  // sensor noise of lighting.noise from rng: the same rng state gives the same bytes.
  CameraImage renderImage(mjModel_* m, mjData_* d, int mjCameraId, int width, int height, const Lighting& lighting,
                          CameraId camera, double timestamp, std::mt19937_64& rng);

  const RenderStages& lastStages() const;

  // The OpenGL that renders: GL_VENDOR, GL_RENDERER, and the platform ("osmesa",
  // "egl-device", "egl-surfaceless"; sim/GlContext.h).
  std::string glVendor() const;
  std::string glRenderer() const;
  std::string glPlatform() const;

 private:
  // Renders into the GL buffer and reads it back into Impl::pixels (rows bottom-up).
  void drawAndRead(mjModel_* m, mjData_* d, int mjCameraId, int width, int height, const Lighting& lighting);

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace nao::sim
