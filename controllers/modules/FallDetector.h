#pragma once
// Falling and fallen from the IMU and the feet (controllers/FallDetector.h does the work).
#include "controllers/FallDetector.h"
#include "representations/perception/FallState.h"
#include "robot/Module.h"
#include "robot/Parameters.h"
#include "robot/SensorData.h"

namespace nao {

template <class V>
void describe(V& v, FallDetector::Params& p) {
  v("fallingAngle", p.fallingAngle, 0.0, 1.6);
  v("fallingRate", p.fallingRate, 0.0, 20.0);
  v("fallenAngle", p.fallenAngle, 0.0, 1.6);
  v("uprightAngle", p.uprightAngle, 0.0, 1.6);
  v("uprightTime", p.uprightTime, 0.0, 10.0);
  v("minFootWeight", p.minFootWeight, 0.0, 10.0);
}

namespace modules {

class FallDetector : public Module<FallDetector, Requires<SensorFrame>, Provides<FallState>> {
 public:
  explicit FallDetector(const ModuleContext& context = {});

 private:
  void update() override;

  nao::FallDetector detector_;
};

}  // namespace modules
}  // namespace nao
