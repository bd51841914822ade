#pragma once
// Holds the NAO's standing posture (knees slightly bent, arms down at the sides).
// It starts softly: the joint targets move from wherever the joints are to the posture over
// softStartTime. An optional ankle balance adds ankleGain * (IMU roll, pitch) to the ankle
// targets. When the fall detector says the robot falls, every joint goes soft (fallStiffness)
// and holds its current angle, as a NAO does to protect its gears; when the robot is upright
// again, the soft start runs anew.
#include "controllers/FallDetector.h"
#include "robot/JointRequest.h"
#include "robot/SensorData.h"

namespace nao {

class StandController {
 public:
  struct Params {
    double softStartTime = 1.0;  // s
    double stiffness = 1.0;      // 0..1 while standing
    double ankleGain = 0.0;      // rad of ankle target per rad of torso tilt (0 = off)
    double fallStiffness = 0.1;  // while falling or fallen
  };

  // The standing posture in LoLA order, rad.
  static JointArray standPosture();

  StandController() = default;
  explicit StandController(const Params& params) : params_(params) {}

  JointRequest update(const SensorFrame& frame, const FallState& fall = {});
  // Starts the soft start again from the next frame's joint angles.
  void reset() { started_ = false; }
  const Params& params() const { return params_; }

 private:
  Params params_;
  bool started_ = false;
  double startTime_ = 0;
  JointArray startPosition_{};
};

}  // namespace nao
