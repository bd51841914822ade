#pragma once
// Getting up from the front or the back. Lying, the robot plays key frames (joint angles,
// smooth interpolation, per-frame stiffness) that bring it into a deep squat with both soles
// flat under its centre of mass; from there it rises on whole-body IK, the COM kept above the
// feet, into the walk's stand posture. Between frames it checks the IMU: a squat that is not
// upright enough when the rise should begin counts as a failed attempt (the engine lets the
// robot relax and tries again). A robot lying on its side first rolls onto its back.
//
// Status (issue 4, measured in the simulator; tests/getup_test.cpp is 'pending'): neither
// sequence gets the robot up yet -- every attempt fails the squat check and the robot lies down
// to try again. From the front, the pike and the knees-in frames leave it kneeling on its shins,
// torso pitched 105-110 deg, the COM ~15 cm ahead of the feet and the soles vertical: with the
// knee at its 121 deg limit and the hip at -88 deg the soles cannot be put flat under the COM
// by the legs alone. From the back, the bridge lifts the pelvis to ~0.2 m with the COM 6-7 cm
// from the feet's centre, then the sit-up frame drops it: the upper body (torso, head, arms:
// 2.95 kg) outweighs the legs (2.4 kg) about the hips, and the arms (2.15 Nm shoulder stall)
// cannot push it forward over the feet. A cross-entropy search over these frames' angles and
// timing (9 angles x 5 frames, 3 pushes each) improved the bridge but found no transition into
// the squat; a different sequence (e.g. legs spread so the feet come beside the hips) is needed.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "controllers/FallDetector.h"
#include "robot/JointRequest.h"
#include "robot/SensorData.h"

namespace nao {

class GetUp {
 public:
  // One key frame: the joints reach `angles` after `duration` seconds.
  struct KeyFrame {
    double duration = 0.5;
    double stiffness = 1.0;
    JointArray angles{};
  };

  struct Params {
    double riseTime = 1.6;         // s from the squat to the stand posture
    double squatMaxTilt = 0.6;     // rad: more tilt than this at the squat = failed attempt
    double torsoHeight = 0.222;    // m (the walk's)
    double footSpacing = 0.10;     // m
    double gyroGain = 0.08;        // rad per rad/s on the ankles while rising
  };

  // The built-in sequences into the squat.
  static std::vector<KeyFrame> frontFrames();
  static std::vector<KeyFrame> backFrames();
  static std::vector<KeyFrame> sideRollFrames(bool lyingOnLeft);
  // The squat both sequences end in: soles flat, COM above them.
  static JointArray squatPosture();

  GetUp() = default;
  explicit GetUp(const Params& params) : params_(params) {}

  // Starts getting up: `lying` from the fall detector (Left/Right roll onto the back first),
  // `stand` the posture to end in.
  void start(const SensorFrame& frame, FallDirection lying, const JointArray& stand);
  // For experiments: play these frames instead of the built-in ones for a front / back start.
  void setFrames(FallDirection lying, const std::vector<KeyFrame>& frames);
  JointRequest update(const SensorFrame& frame);
  bool done() const { return done_; }
  bool failed() const { return failed_; }

 private:
  void startFrames(const SensorFrame& frame, const std::vector<KeyFrame>& frames);
  // The squat's torso height above its flat soles (m) and forward lean (rad).
  static double squatHeight();
  static double squatTorsoPitch();

  Params params_;
  std::vector<KeyFrame> customFront_, customBack_;
  std::vector<KeyFrame> frames_;
  std::size_t frame_ = 0;
  double frameStart_ = 0;
  JointArray from_{};
  JointArray stand_{};
  bool rising_ = false, rollingFirst_ = false;
  double riseStart_ = 0;
  JointArray riseFrom_{};
  bool done_ = true, failed_ = false;
  Eigen::Vector2d gyro_ = Eigen::Vector2d::Zero();
};

}  // namespace nao
