#pragma once
// How fast is the vision? Random simulated scenes (top camera, 640x480 by default) are
// rendered first; then the whole vision runs on each, single-threaded, `repeats` times; per
// frame the median of the repeats counts, and the figures are medians over the frames.
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "perception/FieldDimensions.h"
#include "robot/CameraImage.h"
#include "sim/Lighting.h"

namespace nao::sim {

struct PerceptionBenchOptions {
  int frames = 300;
  int repeats = 3;
  std::uint64_t seed = 1;
  FieldDimensions field;
  std::vector<Lighting> lightings;  // cycled over the frames; empty: default
  CameraId camera = CameraId::Top;
  std::function<void(const std::string& what, int done, int total)> progress;
};

struct PerceptionBenchResult {
  int frames = 0, width = 0, height = 0;
  double totalMsMedian = 0, totalMsP90 = 0, totalMsMean = 0;
  std::map<std::string, double> stageMsMedian;
  nlohmann::json toJson() const;
};

PerceptionBenchResult benchPerception(const PerceptionBenchOptions& options);

}  // namespace nao::sim
