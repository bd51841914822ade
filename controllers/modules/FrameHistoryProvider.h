#pragma once
// Motion cadence: keeps the last half second of joint angles, torso poses and odometry for cognition
// (representations/infrastructure/FrameHistory.h).
#include "representations/infrastructure/FrameHistory.h"
#include "representations/motion/Odometry.h"
#include "representations/perception/TorsoState.h"
#include "robot/Module.h"
#include "robot/Parameters.h"
#include "robot/SensorData.h"

namespace nao::modules {

class FrameHistoryProvider
    : public Module<FrameHistoryProvider, Requires<SensorFrame, TorsoState, Odometry>, Provides<FrameHistory>> {
 public:
  explicit FrameHistoryProvider(const ModuleContext& = {}) {}
  static constexpr double kSpan = 0.5;  // s: an image is never older than this when cognition runs

 private:
  void update() override;
};

}  // namespace nao::modules
