#pragma once
// The NAO camera between the rendered scene and the YUYV bytes: auto exposure and auto white
// balance as control loops that see an image `latencyImages` frames late, rolling shutter and
// motion blur from the camera's rotation, slight defocus, vignetting, and shot plus read noise
// that grow with the analogue gain. One pass over the rendered pixels, no extra render passes.
// Parameters: config/camera_sensor.json; switches: --lighting camera=off, ae=off, ... (Lighting).
// What each effect is and how it was sized: docs/vision/camera-model.md.
#include <cstdint>
#include <deque>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "robot/CameraImage.h"
#include "robot/ExposureWeights.h"

namespace nao::sim {

struct CameraSensorParams {
  bool enabled = true;  // false: the rendered pixels as they are, plus the lighting's flat noise
  bool autoExposure = true;
  bool autoWhiteBalance = true;
  bool vignetting = true;
  bool defocus = true;
  bool motion = false;  // rolling shutter and motion blur (off until the vision compensates them)

  // Auto exposure: brightness b = exposure / nominalExposureMs * gain scales the rendered scene.
  double targetLuma = 75;         // metered mean Y the loop drives the image to (whites just below clipping)
  double nominalExposureMs = 10;  // the exposure at which the image is the rendered scene
  double minExposureMs = 0.5;
  double maxExposureMs = 30;      // then the gain rises (and the noise with it)
  double maxGain = 4;
  double aeRate = 0.35;           // share of the log-brightness error corrected per image
  int latencyImages = 2;          // both loops act on the image this many frames back
  // Auto white balance on near-grey bright pixels (lines, goals, robots, walls).
  double awbRate = 0.25;
  double awbMaxGain = 2.5;        // each channel's gain in [1 / max, max]
  // Optics and sensor.
  double vignettingTop = 0.6;     // corner brightness / centre brightness
  double vignettingBottom = 0.8;
  double defocusSigmaPx = 0.6;    // Gaussian, at 640 px image width (scaled with the width)
  double readoutMs = 30;          // first row to last row
  double shotNoise = 0.03;        // Y variance per Y unit at gain 1

  // Strict: every key known and in range; errors name the file and the key.
  static CameraSensorParams load(const std::string& file);
};

// How one camera stands: the loops' state after an image.
struct CameraExposure {
  double exposureMs = 10;
  double gain = 1;
  Eigen::Vector3d whiteBalance = Eigen::Vector3d::Ones();  // R, G, B gains
  double meteredLuma = 0;  // mean Y of the last image, metered
};

// One physical camera: its loops' state persists from image to image. Exposure, gain and white
// balance act before the sensor clips, so the renderer scales the scene's lights by lightGains()
// and hands the result to process(); vignetting, blur, noise and the YUYV sampling follow there.
class CameraSensor {
 public:
  // The first image in a light: the loops have not seen it yet. The renderer renders the scene
  // at the gains it is told and calls settle() until it returns false (at most three times).
  bool needsSettling(const CameraSensorParams& params) const;
  // rgb rendered at renderedGains: the loops settle as if the camera had been running in this
  // light. True when the image was too clipped or too dark to settle on: render again.
  bool settle(const cv::Mat& rgb, const Eigen::Vector3d& renderedGains, const CameraSensorParams& params,
              CameraId camera);
  // What the scene's lights are scaled by: brightness times the white balance (R, G, B).
  Eigen::Vector3d lightGains(const CameraSensorParams& params) const;

  // rgb: the scene rendered at lightGains(), CV_8UC3 RGB, row 0 at the top (the centre row's
  // exposure at `timestamp`). imageVelocity: how the scene moves in the image (px/s, u right, v
  // down) from the camera's rotation. readNoise: std. dev. in Y units at gain 1 (the lighting's
  // noise; 0: no noise at all, shot noise included). The noise comes from rng: the same state
  // and rng give the same bytes.
  CameraImage process(const cv::Mat& rgb, const CameraSensorParams& params, double readNoise,
                      const Eigen::Vector2d& imageVelocity, CameraId camera, double timestamp, std::mt19937_64& rng);

  const CameraExposure& exposure() const { return state_; }
  // Where the auto exposure meters from the next metering on (the robot program's choice; the
  // default meters the whole image evenly). White balance and clipping look at the whole image.
  void setMeteringWeights(const ExposureWeights& weights) { weights_ = weights; }

 private:
  struct Metering {
    double luma = 0;        // mean Y of the image as it came out (clipped)
    double clipped = 0;     // share of pixels with a channel at 250 or more
    double brightness = 1;  // the brightness it was taken with
    Eigen::Vector3d white = Eigen::Vector3d::Zero();  // mean scene RGB of bright, nearly grey pixels
    int whiteCount = 0;
  };
  Metering meter(const cv::Mat& rgb, const Eigen::Vector3d& renderedGains, const Eigen::Vector3d& gains) const;
  void update(const Metering& m, const CameraSensorParams& params, double aeRate, double awbRate);
  double brightness(const CameraSensorParams& params) const;
  void setBrightness(double b, const CameraSensorParams& params);
  const std::vector<float>& vignetteMap(int width, int height, double corner);

  CameraExposure state_;
  ExposureWeights weights_;
  bool settled_ = false;
  std::deque<Metering> pending_;
  std::vector<float> vignette_;
  int vignetteWidth_ = 0, vignetteHeight_ = 0;
  double vignetteCorner_ = -1;
};

// Zero-mean noise for a YUYV image: std. dev. sigma on Y, sigma/2 on U and V, flat.
void addSensorNoise(CameraImage& image, double sigma, std::mt19937_64& rng);

}  // namespace nao::sim
