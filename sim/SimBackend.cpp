#include "sim/SimBackend.h"

#include "robot/Error.h"
#include "sim/World.h"

namespace nao::sim {

SimBackend::SimBackend(World& world, int robot, bool ownsStepping)
    : world_(world), robot_(robot), ownsStepping_(ownsStepping) {
  if (robot < 0 || robot >= world.robotCount())
    throw Error("SimBackend", "robot " + std::to_string(robot) + " is not in the world");
  nextDue_ = {world.time(), world.time() + kCameraPeriod / 2};
}

RobotInfo SimBackend::robotInfo() const {
  RobotInfo info;
  info.bodyId = "sim-r" + std::to_string(robot_) + "-body";
  info.headId = "sim-r" + std::to_string(robot_) + "-head";
  return info;
}

bool SimBackend::waitForSensors(SensorFrame& frame) {
  if (!stopReason_.empty()) return false;
  if (ownsStepping_) {
    try {
      world_.stepCycle();
    } catch (const Error& e) {
      stopReason_ = e.what();
      return false;
    }
  }
  frame = world_.sensors(robot_);
  frame.time = world_.time();
  frame.cycle = cycle_++;
  if (imageSource_) {
    const double now = world_.time();
    for (int c = 0; c < kNumCameras; ++c) {
      if (now + 1e-9 < nextDue_[c]) continue;
      const auto camera = static_cast<CameraId>(c);
      CameraImage image = imageSource_(camera, now, exposureWeights_[c]);
      image.camera = camera;
      image.timestamp = now;
      pending_[c] = std::move(image);
      nextDue_[c] += kCameraPeriod;
      if (nextDue_[c] <= now) nextDue_[c] = now + kCameraPeriod;  // fell behind: no burst of images
    }
  }
  return true;
}

bool SimBackend::takeImage(CameraId camera, CameraImage& image) {
  auto& slot = pending_[static_cast<int>(camera)];
  if (!slot) return false;
  image = std::move(*slot);
  slot.reset();
  return true;
}

void SimBackend::sendRequest(const JointRequest& joints, const LedRequest& leds) {
  world_.setJointRequest(robot_, joints);
  request_ = joints;
  leds_ = leds;
}

}  // namespace nao::sim
