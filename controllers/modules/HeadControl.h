#pragma once
// Where the cameras look: the behaviour's HeadMotionRequest -> head joint targets within the
// joint limits and speed limits (controllers/HeadControl.h does the work).
#include "controllers/HeadControl.h"
#include "representations/behavior/HeadMotionRequest.h"
#include "representations/motion/HeadJointRequest.h"
#include "representations/perception/TorsoState.h"
#include "robot/Module.h"
#include "robot/Parameters.h"
#include "robot/SensorData.h"

namespace nao {

template <class V>
void describe(V& v, HeadControl::Params& p) {
  v("maxYawSpeed", p.maxYawSpeed, 0.0, 10.0);
  v("maxPitchSpeed", p.maxPitchSpeed, 0.0, 10.0);
  v("maxAcceleration", p.maxAcceleration, 0.1, 200.0);
  v("arrivedTolerance", p.arrivedTolerance, 0.0, 0.5);
  v("stillSpeed", p.stillSpeed, 0.0, 5.0);
  v("settleTime", p.settleTime, 0.0, 5.0);
}

namespace modules {

class HeadControl
    : public Module<HeadControl, Requires<SensorFrame, HeadMotionRequest, TorsoState>, Provides<HeadJointRequest>> {
 public:
  explicit HeadControl(const ModuleContext& context = {});
  const nao::HeadControl& control() const { return head_; }

 private:
  void update() override;

  nao::HeadControl head_;
};

}  // namespace modules
}  // namespace nao
