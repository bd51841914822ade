#pragma once
// The motion engine: turns the behaviour's MotionRequest into one JointRequest per 12 ms cycle
// (83 Hz). It owns the motions -- the walk (which also stands), walking to a robot-relative
// target on odometry, the kick, the get-up, sitting down, playing dead -- and moves between
// them smoothly: every motion starts and ends in the walk's stand posture (or a posture the
// next one interpolates from), and the head follows HeadControl unless a motion needs it.
// When the fall detector says the robot falls, whatever runs is dropped for a safe fall
// (arms out, knees bent, stiffness low); lying, the robot gets up when the request wants it on
// its feet (or asks GetUp) and stays down for SitDown / PlayDead.
#include <memory>

#include "controllers/FallDetector.h"
#include "controllers/GetUp.h"
#include "controllers/Kick.h"
#include "controllers/Walk.h"
#include "representations/behavior/ArmMotionRequest.h"
#include "representations/behavior/MotionRequest.h"
#include "representations/motion/HeadJointRequest.h"
#include "representations/motion/MotionInfo.h"
#include "representations/motion/Odometry.h"
#include "robot/JointRequest.h"
#include "robot/SensorData.h"

namespace nao {

class MotionEngine {
 public:
  struct Params {
    Walk::Params walk;
    Kick::Params kick;
    GetUp::Params getUp;
    double transitionTime = 0.8;   // s, interpolation into the walk's stand posture
    double sitDownTime = 1.5;      // s
    double playDeadStiffness = 0.0;
    // WalkTo: speeds towards the target (P control on the odometry's remaining offset).
    double walkToGain = 1.5;              // 1/s for translation near the target
    double walkToTurnGain = 1.2;          // 1/s for rotation
    double walkToMaxTurn = 0.8;           // rad/s
    double walkToDeceleration = 0.25;     // m/s^2: the approach slows down to stop in time
    double walkToNearDistance = 0.3;      // m: closer, the robot aligns to the target's heading
    double walkToNearSpeed = 0.1;         // m/s, per axis, near the target
    double walkToPositionTolerance = 0.01;  // m
    double walkToAngleTolerance = 0.03;     // rad
    // Once stopped, the robot walks again only when the stand pose is this many tolerances off.
    double walkToResumePosition = 2.5, walkToResumeAngle = 2.0;
    // The kick pose reached: the kick's strike follows the ball and turns the foot by what is
    // left. Twice the old 0.015 m and 0.06 rad saves the approach's slow last centimetres:
    // `kick --trials 12` median time to the kick's end 7.96 s against 10.24 s, travel 6.48 m
    // against 6.53 m, direction error median 1.6 deg against 1.2 deg (docs/plans/one-vs-one.md).
    double kickPositionTolerance = 0.03;    // m
    double kickAngleTolerance = 0.1;        // rad
    double armRaiseTime = 0.6;              // s, down to up (and back)
  };

  MotionEngine() : MotionEngine(Params{}) {}
  explicit MotionEngine(const Params& params);

  JointRequest update(const SensorFrame& frame, const FallState& fall, const MotionRequest& request,
                      const HeadJointRequest& head = {}, const ArmMotionRequest& arm = {});
  // The raised arm's joint angles (ShoulderPitch, ShoulderRoll, ElbowYaw, ElbowRoll): up above
  // the head, slightly outwards, palm inwards.
  static std::array<double, 4> raisedArm(ArmMotionRequest::Arm side);

  const MotionInfo& info() const { return info_; }
  const Odometry& odometry() const { return odometry_; }
  const Walk& walk() const { return walk_; }
  Walk& walk() { return walk_; }
  GetUp& getUp() { return getUp_; }  // e.g. GetUp::setFrames for experiments
  // The channels walk_trace and walk_to_trace go to (not owned; null: none).
  void setDebug(DebugChannels* debug) {
    debug_ = debug ? debug : &DebugChannels::none();
    walk_.setDebug(debug);
  }
  const Params& params() const { return params_; }

 private:
  enum class State { Start, Transition, Walk, Kick, Falling, Lying, GetUp, SitDown, Sitting, PlayDead };

  void enter(State state, const SensorFrame& frame);
  JointRequest interpolate(const SensorFrame& frame, const JointArray& goal, double duration, double stiffness);
  // byStopPose: steer by Walk::stopPoseEstimate (WalkTo), else by standPoseEstimate (the kick's approach).
  Pose2 walkToSpeed(const Pose2& target, double positionTolerance, double angleTolerance, bool byStopPose);
  // One walk_to_trace line (every 8th cycle): the target relative to the robot, the speed, the phase.
  void traceWalkTo(const SensorFrame& frame, const Pose2& speed, const char* what) const;
  Pose2 kickPose(const Eigen::Vector2d& ball, double direction, bool leftFoot) const;
  bool wantsFeet(const MotionRequest& request) const;
  void applyHead(JointRequest& out, const HeadJointRequest& head) const;
  void applyArm(JointRequest& out, const SensorFrame& frame, const ArmMotionRequest& arm);

  Params params_;
  DebugChannels* debug_ = &DebugChannels::none();
  Walk walk_;
  Kick kick_;
  GetUp getUp_;
  State state_ = State::Start;
  double stateStart_ = 0;
  JointArray from_{};       // the joint angles an interpolation starts from
  JointArray lastOutput_{};
  MotionInfo info_;
  Odometry odometry_;
  Pose2 walkOdometryBase_;  // odometry when the current walk segment began
  Pose2 walkOdometryLast_;  // the walk's odometry at the last cycle (to accumulate deltas)
  int walkTargetId_ = -1;
  Pose2 walkTarget_;        // in the odometry frame
  bool walkToStopped_ = false;
  int kickId_ = -1;
  bool kickLeft_ = true;
  int doneKickId_ = -1;
  ArmMotionRequest::Arm armSide_ = ArmMotionRequest::Arm::Right;  // the arm raised or being lowered
  double armBlend_ = 0;     // 0 down (the motion's own arm) .. 1 up
  double armLastTime_ = -1;
};

}  // namespace nao
