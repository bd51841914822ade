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
#include "robot/ExposureWeights.h"
#include "sim/Lighting.h"

struct mjModel_;
struct mjData_;

namespace nao::sim {

// Writes `lighting` into the model's sun light (named "sun") and headlight, and the sun's
// direction into d's light frames (so no mj_forward is needed before rendering). gains scale
// the lights' R, G and B (the camera model's exposure and white balance).
void applyLighting(mjModel_* m, mjData_* d, const Lighting& lighting,
                   const Eigen::Vector3d& gains = Eigen::Vector3d::Ones());

// Where a camera image's time went (ms): the scene's update from the state, the draw calls,
// reading the pixels back (it waits for the drawing to finish), the camera sensor's pass
// (sim/CameraSensor.h: effects, YUYV, noise). renderRgb sets the first three. A camera's first
// image in a light also renders to settle its loops; that time is not in these.
struct RenderStages {
  double scene = 0, draw = 0, read = 0, sensor = 0;
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

  // renderRgb through the NAO camera's model (lighting.camera, sim/CameraSensor.h; its loops keep
  // their state per mjCameraId) into YUYV (BT.601 full range, U/V averaged over each pixel pair),
  // with the camera's rotation from d for the rolling shutter and the motion blur. The noise comes
  // from rng: the same rng state and the same image history give the same bytes. The auto
  // exposure meters with `metering` (the robot program's weights; default: the whole image).
  CameraImage renderImage(mjModel_* m, mjData_* d, int mjCameraId, int width, int height, const Lighting& lighting,
                          CameraId camera, double timestamp, std::mt19937_64& rng, const ExposureWeights& metering);

  // Forgets the cameras' exposure and white-balance state: the next image of each camera starts
  // settled in its light (a new trial in another light, not a step in the light).
  void resetCameraSensors();
  // The exposure state of MuJoCo camera mjCameraId after its last image (defaults before one).
  CameraExposure cameraExposure(int mjCameraId) const;

  const RenderStages& lastStages() const;

  // The OpenGL that renders: GL_VENDOR, GL_RENDERER, and the platform ("osmesa",
  // "egl-device", "egl-surfaceless"; sim/GlContext.h).
  std::string glVendor() const;
  std::string glRenderer() const;
  std::string glPlatform() const;

 private:
  // Renders into the GL buffer and reads it back into Impl::pixels (rows bottom-up).
  void drawAndRead(mjModel_* m, mjData_* d, int mjCameraId, int width, int height, const Lighting& lighting,
                   const Eigen::Vector3d& gains = Eigen::Vector3d::Ones());

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace nao::sim
