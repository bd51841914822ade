#pragma once
// Lighting of a simulated scene and the camera that sees it: a preset name from
// config/lighting.json or a "key=value,..." list (intensity, temperature, shadows, elevation,
// azimuth, ambient, noise; the camera model's switches camera, ae, awb, vignetting, defocus,
// motion = on|off over config/camera_sensor.json beside the presets file).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sim/CameraSensor.h"

namespace nao::sim {

struct Lighting {
  std::string name = "default";
  double intensity = 1.0;      // scales the sun (directional) light
  double temperature = 5500;   // K; tints the light (2700 warm .. 6500 cold)
  bool shadows = false;        // hard shadows from the sun light
  double elevation = 60;       // deg above the horizon of the sun light
  double azimuth = 120;        // deg, field frame, direction the light comes from
  double ambient = 0.3;        // ambient term, scaled by intensity
  double noise = 1.5;          // read noise at gain 1, std. dev. in Y units (0..255), seeded
  CameraSensorParams camera;    // the NAO camera between the scene and the bytes

  // RGB of a black body at `temperature`, normalised so that the brightest channel is 1.
  Eigen::Vector3d colour() const;

  // spec: a preset name or a key=value list; presets come from presetsFile
  // (config/lighting.json). Throws nao::Error naming the flag/file and the key.
  static Lighting parse(const std::string& spec, const std::string& presetsFile);
  // The presets an evaluation sweeps over with --lighting sweep; "sweep,key=value,..." applies
  // the overrides to each (e.g. sweep,camera=off). Throws as parse does.
  static std::vector<Lighting> sweep(const std::string& presetsFile, const std::string& overrides = "");
};

}  // namespace nao::sim
