#include "controllers/RobotProgram.h"

#include <memory>

#include "controllers/FallDetector.h"
#include "controllers/HeadControl.h"
#include "controllers/MotionEngine.h"
#include "controllers/MotionRequest.h"

namespace nao {
namespace {

// IMU angles + leg kinematics + calibration -> both cameras' matrices.
class CameraMatrixProvider : public Module {
 public:
  CameraMatrixProvider() {
    require<SensorFrame, CameraCalibration, RobotProgramConfig, CameraImages>();
    provide<CameraMatrices, TorsoState>();
  }
  std::string name() const override { return "CameraMatrixProvider"; }
  void update(Blackboard& bb) override {
    const auto& frame = bb.read<SensorFrame>();
    const auto& calib = bb.read<CameraCalibration>();
    auto& config = bb.write<RobotProgramConfig>();
    // The intrinsics follow the resolution the camera actually delivers.
    for (int c = 0; c < kNumCameras; ++c)
      if (const auto& img = bb.read<CameraImages>().latest[c];
          img && (img->width != config.intrinsics[c].width || img->height != config.intrinsics[c].height))
        config.intrinsics[c] = CameraIntrinsics::fromFovY(img->width, img->height);
    auto& torso = bb.write<TorsoState>();
    torso.robotToTorso = robotToTorso(frame.joints.position, frame.inertial.angle.x(), frame.inertial.angle.y());
    auto& matrices = bb.write<CameraMatrices>();
    for (CameraId cam : {CameraId::Top, CameraId::Bottom})
      matrices.matrix[static_cast<int>(cam)] = computeCameraMatrix(
          frame.joints.position, torso.robotToTorso, cam, calib, config.intrinsics[static_cast<int>(cam)]);
  }
};

class FallDetectorModule : public Module {
 public:
  FallDetectorModule() {
    require<SensorFrame>();
    provide<FallState>();
  }
  std::string name() const override { return "FallDetector"; }
  void update(Blackboard& bb) override { bb.write<FallState>() = detector_.update(bb.read<SensorFrame>()); }

 private:
  FallDetector detector_;
};

// Where the cameras look: the behaviour's HeadMotionRequest -> head joint targets.
class HeadControlModule : public Module {
 public:
  HeadControlModule() {
    require<SensorFrame, HeadMotionRequest, TorsoState>();
    provide<HeadJointRequest>();
  }
  std::string name() const override { return "HeadControl"; }
  void update(Blackboard& bb) override {
    bb.write<HeadJointRequest>() =
        head_.update(bb.read<SensorFrame>(), bb.read<HeadMotionRequest>(), bb.read<TorsoState>().robotToTorso);
  }

 private:
  HeadControl head_;
};

// The body: the behaviour's MotionRequest -> joint requests (stand, walk, kick, get up, ...),
// the odometry and what the motion does.
class MotionEngineModule : public Module {
 public:
  explicit MotionEngineModule(const MotionEngine::Params& params) : engine_(params) {
    require<SensorFrame, FallState, MotionRequest, HeadJointRequest>();
    provide<JointRequest, MotionInfo, Odometry>();
  }
  std::string name() const override { return "MotionEngine"; }
  void update(Blackboard& bb) override {
    bb.write<JointRequest>() =
        engine_.update(bb.read<SensorFrame>(), bb.read<FallState>(), bb.read<MotionRequest>(), bb.read<HeadJointRequest>());
    bb.write<MotionInfo>() = engine_.info();
    bb.write<Odometry>() = engine_.odometry();
  }

 private:
  MotionEngine engine_;
};

}  // namespace

RobotProgram::RobotProgram(const RobotProgramConfig& config) {
  blackboard_.write<RobotProgramConfig>() = config;
  blackboard_.write<CameraCalibration>() = config.calibration;
  blackboard_.write<MotionRequest>() = MotionRequest{};  // stand
  blackboard_.write<HeadMotionRequest>() = HeadMotionRequest{};
  // MotionRequest and HeadMotionRequest come from the behaviour (or a scenario) until a
  // behaviour module provides them.
  pipeline_.inputs<SensorFrame, CameraImages, CameraCalibration, RobotProgramConfig, MotionRequest, HeadMotionRequest>();
  pipeline_.add(std::make_unique<CameraMatrixProvider>());
  pipeline_.add(std::make_unique<FallDetectorModule>());
  pipeline_.add(std::make_unique<HeadControlModule>());
  pipeline_.add(std::make_unique<MotionEngineModule>(config.motion));
  pipeline_.sort();
}

bool RobotProgram::cycle(Backend& backend) {
  auto& frame = blackboard_.write<SensorFrame>();
  if (!backend.waitForSensors(frame)) return false;
  auto& images = blackboard_.write<CameraImages>();
  for (CameraId cam : {CameraId::Top, CameraId::Bottom}) {
    CameraImage img;
    auto& slot = images.latest[static_cast<int>(cam)];
    if (backend.takeImage(cam, img))
      slot = std::move(img);
    else
      slot.reset();
  }
  pipeline_.update(blackboard_);
  backend.sendRequest(blackboard_.read<JointRequest>(), blackboard_.write<LedRequest>());
  return true;
}

}  // namespace nao
