#pragma once
// The robot program against the simulator for a given time: one NAO, both cameras at 30 Hz
// (or none), ground truth recorded. Used by `run --backend sim` and `bench sim`.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "perception/CameraCalibration.h"
#include "perception/FieldDimensions.h"
#include "robot/Debug.h"
#include "sim/Lighting.h"

namespace nao::sim {

struct SimRunOptions {
  FieldDimensions field;
  std::string robotModel;  // MJCF path; empty = models/nao_v6.xml
  double seconds = 10;
  Eigen::Vector3d pose{-3.2, -3.0, M_PI / 2};  // the calibration position: side line, own penalty mark
  CameraCalibration miscalibration;            // injected into the simulated hardware
  Lighting lighting;
  bool cameras = true;
  std::string imagesDir;                       // non-empty: PNGs of both cameras once a second + field view
  std::uint64_t seed = 1;
  std::function<void(double simTime)> progress;  // called about once per simulated second
  DebugChannels* debug = nullptr;                // the robot program's debug channels (not owned); null: none
};

struct SimRunResult {
  double simSeconds = 0, wallSeconds = 0;
  std::uint64_t cycles = 0;
  int imagesTop = 0, imagesBottom = 0;  // delivered by the simulated cameras
  long imagesProcessedTop = 0, imagesProcessedBottom = 0;  // run through the robot program's cognition
  std::vector<double> renderMsTop, renderMsBottom;
  bool fell = false;
  double torsoHeightMin = 0, torsoHeightMax = 0;
  Eigen::Vector3d finalPose = Eigen::Vector3d::Zero();
  std::vector<std::string> imagesWritten;
  std::vector<std::string> moduleOrder;
};

SimRunResult runSim(const SimRunOptions& options);

double median(std::vector<double> v);

}  // namespace nao::sim
