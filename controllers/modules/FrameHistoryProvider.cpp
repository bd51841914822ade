#include "controllers/modules/FrameHistoryProvider.h"

#include <cmath>

#include "robot/ModuleRegistry.h"

namespace nao::modules {

void FrameHistoryProvider::update() {
  const SensorFrame& frame = in<SensorFrame>();
  auto& entries = out<FrameHistory>().entries;
  if (!std::isfinite(frame.time)) return;
  // A clock that went backwards (a restarted backend) starts the history anew.
  if (!entries.empty() && frame.time < entries.back().time) entries.clear();
  entries.push_back(
      {frame.time, frame.joints.position, in<TorsoState>().robotToTorso, in<Odometry>().pose, frame.inertial.angle});
  while (entries.size() > 2 && entries.back().time - entries.front().time > kSpan) entries.pop_front();
}

NAO_REGISTER_MODULE(FrameHistoryProvider);

}  // namespace nao::modules
