#pragma once
// What a simulated world contains: the field (from field_dimensions.json), robots and balls.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "perception/FieldDimensions.h"
#include "sim/VenueLook.h"

namespace nao::sim {

struct CameraResolution {
  int width = 640;
  int height = 480;
};

struct SceneSpec {
  FieldDimensions field;
  std::vector<Eigen::Vector3d> robots{Eigen::Vector3d::Zero()};  // (x, y, theta) field frame, m / rad
  std::vector<Eigen::Vector3d> balls;                            // (x, y, z) centre; z = 0.05 rests on the carpet
  CameraResolution top{640, 480};
  CameraResolution bottom{320, 240};
  double physicsStep = 0.002;  // s; the 12 ms cycle is 6 steps
  std::string robotModel;      // MJCF path; empty = models/nao_v6.xml
  VenueLook venue;             // how the carpet, the paint and the hall look ("none": the diagram)
  std::uint64_t venueSeed = 1;  // where the venue's people, tables, boards stand; its textures
};

}  // namespace nao::sim
