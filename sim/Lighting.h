#pragma once
// Lighting of a simulated scene: a preset name from config/lighting.json or a
// "key=value,..." list (intensity, temperature, shadows, elevation, azimuth, ambient, noise).
#include <string>
#include <vector>

#include <Eigen/Core>

namespace nao::sim {

struct Lighting {
  std::string name = "default";
  double intensity = 1.0;      // scales the sun (directional) light
  double temperature = 5500;   // K; tints the light (2700 warm .. 6500 cold)
  bool shadows = false;        // hard shadows from the sun light
  double elevation = 60;       // deg above the horizon of the sun light
  double azimuth = 120;        // deg, field frame, direction the light comes from
  double ambient = 0.3;        // ambient term, scaled by intensity
  double noise = 1.5;          // sensor noise, std. dev. in Y units (0..255), seeded

  // RGB of a black body at `temperature`, normalised so that the brightest channel is 1.
  Eigen::Vector3d colour() const;

  // spec: a preset name or a key=value list; presets come from presetsFile
  // (config/lighting.json). Throws nao::Error naming the flag/file and the key.
  static Lighting parse(const std::string& spec, const std::string& presetsFile);
  // The presets an evaluation sweeps over with --lighting sweep.
  static std::vector<Lighting> sweep(const std::string& presetsFile);
};

}  // namespace nao::sim
