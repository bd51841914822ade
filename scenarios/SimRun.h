#pragma once
// The robot program against the simulator for a given time: one NAO, both cameras at 30 Hz
// (or none), ground truth recorded. Used by `run --backend sim` and `bench sim`.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "perception/CameraCalibration.h"
#include "perception/FieldDimensions.h"
#include "representations/modeling/BallModel.h"
#include "representations/modeling/RobotPose.h"
#include "robot/Debug.h"
#include "sim/CameraRenderer.h"
#include "sim/Lighting.h"
#include "sim/VenueLook.h"

namespace nao::sim {

struct SimRunOptions {
  FieldDimensions field;
  std::string robotModel;  // MJCF path; empty = models/nao_v6.xml
  VenueLook venue;         // how the venue looks (sim/VenueLook.h)
  double seconds = 10;
  Eigen::Vector3d pose{-3.2, -3.0, M_PI / 2};  // the calibration position: side line, own penalty mark
  CameraCalibration miscalibration;            // injected into the simulated hardware
  Lighting lighting;
  bool cameras = true;
  std::string imagesDir;  // non-empty: annotated views of both cameras and a field view, once a second
  std::optional<Pose2> goTo;                   // the behaviour's command: walk to this field pose
  std::optional<Eigen::Vector2d> ball;         // a ball lying here (field frame)
  std::uint64_t seed = 1;
  std::function<void(double simTime)> progress;  // called about once per simulated second
  DebugChannels* debug = nullptr;                // the robot program's debug channels (not owned); null: none
};

// Once a simulated second: the truth beside the robot program's belief.
struct SimRunSecond {
  double t = 0;
  Eigen::Vector3d truePose = Eigen::Vector3d::Zero();  // (x, y, theta)
  RobotPose estimate;      // moved to this cycle by the odometry since its image
  double positionError = -1, headingError = -1;  // m, rad; -1 while the estimate is not valid
  std::optional<Eigen::Vector2d> trueBall;       // field frame
  BallModel ball;
  double ballError = -1;   // m, robot frame (the model against the truth relative to the true pose); -1: no model
};

struct SimRunResult {
  double simSeconds = 0, wallSeconds = 0;
  std::uint64_t cycles = 0;
  int imagesTop = 0, imagesBottom = 0;  // delivered by the simulated cameras
  long imagesProcessedTop = 0, imagesProcessedBottom = 0;  // run through the robot program's cognition
  std::vector<double> renderMsTop, renderMsBottom;
  std::vector<RenderStages> renderStagesTop, renderStagesBottom;  // each image's, as renderMs*
  std::string glVendor, glRenderer, glPlatform;  // the renderer's OpenGL, when cameras ran
  bool fell = false;
  double torsoHeightMin = 0, torsoHeightMax = 0;
  Eigen::Vector3d finalPose = Eigen::Vector3d::Zero();
  std::vector<std::string> imagesWritten;
  std::vector<std::string> moduleOrder;
  std::vector<std::string> motionModules, cognitionModules;
  // After every cognition run with a valid estimate (and after the first 2 s): its errors
  // against the truth at that cycle (the estimate moved by the odometry since its image).
  std::vector<double> positionErrors, headingErrors;  // m, rad
  std::vector<double> ballErrors;                     // m, robot frame, while a ball model is valid
  long validRuns = 0, cognitionRunsTotal = 0;
  std::vector<SimRunSecond> seconds;
  RobotPose finalEstimate;  // as in SimRunSecond
  BallModel finalBall;
  std::vector<double> motionMs, cognitionMs;  // wall time per motion cycle and per cognition run
  std::vector<double> cognitionMsTop, cognitionMsBottom;  // cognitionMs by the image's camera
};

SimRunResult runSim(const SimRunOptions& options);

double median(std::vector<double> v);

}  // namespace nao::sim
