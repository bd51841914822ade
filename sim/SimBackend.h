#pragma once
// The robot program's hardware when it runs in the simulator: one robot of a World.
//
// With ownsStepping (one robot, one program) waitForSensors advances the world by one 12 ms
// cycle; with several robots the scenario steps the world once per cycle and each robot's
// SimBackend only reads its sensors. Camera images come from an image source the scenario
// sets (the OSMesa renderer); each camera is due at 30 Hz, the bottom one half a period after
// the top one so that the two renders fall into different cycles.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "robot/Backend.h"

namespace nao::sim {

class World;

class SimBackend : public Backend {
 public:
  // Renders camera `camera` of this backend's robot at world time `time`, its auto exposure
  // metering with `weights` (the robot program's, robot/ExposureWeights.h).
  using ImageSource = std::function<CameraImage(CameraId camera, double time, const ExposureWeights& weights)>;

  SimBackend(World& world, int robot, bool ownsStepping = true);

  std::string name() const override { return "sim"; }
  RobotInfo robotInfo() const override;  // ids "sim-r<N>-body" / "sim-r<N>-head"
  bool waitForSensors(SensorFrame& frame) override;
  bool takeImage(CameraId camera, CameraImage& image) override;
  void sendRequest(const JointRequest& joints, const LedRequest& leds) override;
  void setExposureWeights(CameraId camera, const ExposureWeights& weights) override {
    exposureWeights_[static_cast<int>(camera)] = weights;
  }
  const ExposureWeights& exposureWeights(CameraId camera) const { return exposureWeights_[static_cast<int>(camera)]; }
  std::string stopReason() const override { return stopReason_; }

  void setImageSource(ImageSource source) { imageSource_ = std::move(source); }
  // Makes the next waitForSensors return false with this reason (end of a scenario).
  void stop(const std::string& reason) { stopReason_ = reason.empty() ? "stopped" : reason; }

  World& world() { return world_; }
  int robot() const { return robot_; }
  std::uint64_t cycle() const { return cycle_; }
  const LedRequest& leds() const { return leds_; }
  const JointRequest& lastRequest() const { return request_; }

 private:
  World& world_;
  int robot_;
  bool ownsStepping_;
  std::uint64_t cycle_ = 0;
  ImageSource imageSource_;
  std::array<double, kNumCameras> nextDue_{};
  std::array<ExposureWeights, kNumCameras> exposureWeights_;
  std::array<std::optional<CameraImage>, kNumCameras> pending_;
  JointRequest request_{};
  LedRequest leds_{};
  std::string stopReason_;
};

}  // namespace nao::sim
