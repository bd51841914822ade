#pragma once
// The kick: from the walk's stand posture, a straight kick with the foot on the ball's side.
// The motion engine first walks the robot to the kick pose (facing the requested direction,
// the ball in front of the kicking foot); the kick itself then only corrects what is left:
// the strike follows the ball's actual position and turns the foot by the remaining angle.
//
// Phases (the soles' poses in the stand frame, the COM placed by whole-body IK):
//   shift    the COM moves over the support sole (slow enough to be quasi-static);
//   lift     the kicking foot rises and swings back (wind-up);
//   strike   its target jumps through the ball: the servos run at their torque-speed limit,
//            hip, knee and ankle together, which is where the ball speed comes from;
//   retract  the foot comes back under the hip, then down;
//   return   the COM moves back between the feet.
// Balance on one leg: the COM stays above the support sole (the kicking leg's motion is in the
// COM model), gyro damping on the support ankle, and the support leg's sag is compensated
// from the weight it carries (FSRs).
//
// Direction: measured over kicks in the simulator, the ball left ~4 deg inward of the foot's
// path (the toe meets it slightly outside its centre line while the leg swings in), so the
// foot aims yawBias outward and the strike path runs strikeInward towards the ball's centre.
// Distance: hip pitch, knee and ankle all run at their no-load speeds (~6.4 rad/s) through the
// strike; the sole peaks at ~2 m/s just as it meets the ball. The foam ball rebounds off the
// foot (restitution ~0.5, sim/SceneBuilder.cpp), so it leaves at ~2.8 m/s, without topspin: it
// slides (or hops) until it rolls at ~5/7 of that, and rolls ~3 m on the simulated carpet.
// The toe waits ballGap behind the ball: the walk's last step swings the foot ahead of its
// stand position, and a closer ball would be pushed away before the kick.
#include <Eigen/Core>

#include "representations/behavior/MotionRequest.h"
#include "robot/JointRequest.h"
#include "robot/SensorData.h"

namespace nao {

class Kick {
 public:
  struct Params {
    double torsoHeight = 0.222;   // m (the walk's)
    double footSpacing = 0.10;    // m (the walk's)
    double shiftTime = 0.7;       // s
    double liftTime = 0.35;
    double strikeTime = 0.082;     // s: the target's sweep through the ball
    double holdTime = 0.15;       // s after the strike
    double retractTime = 0.35;
    double lowerTime = 0.3;
    double returnTime = 0.7;
    double comInward = 0.01;      // m: the COM over the support sole, towards the inner edge
    double comForward = 0.015;    // m
    double liftHeight = 0.09;     // m
    double windUp = 0.08;         // m behind the sole's stand position
    double strikeHeight = 0.06;   // m: sole height at the strike (the servos lag: it passes lower)
    double followThrough = 0.12;  // m past the ball's contact point
    double strikeReach = 0.13;    // m: the strike ends at most this far in front of the stand position
    double windUpPitch = -0.2;    // rad, the kicking sole's pitch at the wind-up (Ry: > 0 toe down)
    double strikePitch = 0.2;     // rad, at the end of the strike
    double ballGap = 0.04;        // m between the toe and the ball in the kick pose
    double maxFootYaw = 0.35;     // rad: the remaining direction error the foot corrects
    double yawBias = 0.1;         // rad: the kicking foot aims this much outward of the direction
    double strikeInward = 0.02;   // m: the strike path this much inward of the ball's centre line
    double gyroPitchGain = 0.1;   // rad per rad/s on the support ankle
    double gyroRollGain = 0.1;
    double servoGain = 60;        // N m / rad (sag compensation, see Walk)
  };

  // Where the ball must be (robot frame) for a kick with the left / right foot: in front of
  // the kicking sole, kick direction = the robot's heading.
  static Eigen::Vector2d ballTarget(bool leftFoot, const Params& params);

  Kick() = default;
  explicit Kick(const Params& params) : params_(params) {}

  // Starts from the walk's stand posture `stand`; ball in the robot frame, direction (rad,
  // robot frame) the ball should go.
  void start(const SensorFrame& frame, const JointArray& stand, const Eigen::Vector2d& ball, double direction);
  JointRequest update(const SensorFrame& frame);
  bool done() const { return done_; }
  bool leftFoot() const { return left_; }
  double duration() const;

 private:
  Params params_;
  JointArray stand_{};
  double startTime_ = 0;
  bool done_ = true;
  bool left_ = true;
  Eigen::Vector2d strikePoint_ = Eigen::Vector2d::Zero();  // sole position at the end of the strike (stand frame)
  Eigen::Vector2d ballStart_ = Eigen::Vector2d::Zero();
  double footYaw_ = 0;
  Eigen::Vector2d torsoOffset_ = Eigen::Vector2d::Zero();  // robot frame origin in the stand frame
  Eigen::Vector2d torsoGuess_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d gyro_ = Eigen::Vector2d::Zero();
  double leftShare_ = 0.5;
};

}  // namespace nao
