#pragma once
// The robot's horizontal velocity from the legs' kinematics checked by the IMU (a Kalman filter
// per cycle), for the walk's odometry.
//
// Why. The odometry's translation is the torso's motion over a foot that stands still. Each
// step there are a few cycles where no foot does: the swing foot lands 10-70 ms late and slides
// or bounces on its heel while the other is already lifting; the foot the odometry follows then
// moves by up to 8 mm in a cycle against the torso's 4 mm (traced against the simulator's
// truth, these cycles made most of a randomised 3 m walk-to's error). The FSRs cannot tell
// (a bouncing foot reads 0-15 kg from cycle to cycle); the accelerometer can. Integrated over
// one cycle, its specific force less gravity (the IMU's tilt) and less the change of the IMU's
// lever-arm velocity (it sits 11 cm above the robot frame's origin, the torso rocks at
// 0.5 rad/s) predicts the next cycle's displacement to 0.025 mm (median; 99 % within 0.15 mm,
// tests/odometry_test.cpp), where a loaded foot's kinematics scatter by 0.2 mm (median) to
// 4 mm (99 %) a cycle.
//
// So: state = (velocity, accelerometer bias), per horizontal axis, in the robot frame. Predict
// with the accelerometer; each foot's kinematic velocity is a measurement whose variance grows
// as its load share shrinks; a measurement more than `gate` standard deviations from the
// prediction (in 2-D) is a foot that moved (rejected). The bias state, fixed to the body, takes
// up a slowly wrong tilt (a real IMU's angle is off by a degree or so: 0.17 m/s^2), which the
// kinematics observe over time. The mean velocity over a long walk is still the kinematics' (the filter's prediction
// has no information of its own about a steady creep), but a foot that slides for a few cycles
// no longer moves the odometry.
#include <Eigen/Core>

namespace nao {

// The change of the robot frame origin's mean horizontal velocity from one cycle to the next,
// as the IMU measures it: the cycles' mean specific force less gravity (trapezoid across the
// two cycles), less the change of the IMU's velocity about the origin (w x r). In the robot
// frame at this cycle's start. NaN on the first cycle (and after reset()).
class ImuVelocityChange {
 public:
  // tilt: the torso's roll and pitch (torso -> yaw-free frame); accelerometer and gyroscope:
  // the cycle's mean readings in the torso frame; turn: the robot frame's rotation over this
  // cycle; imu: the IMU's position in the torso frame.
  Eigen::Vector2d update(const Eigen::Matrix3d& tilt, const Eigen::Vector3d& accelerometer, const Eigen::Vector3d& gyroscope,
                         double turn, double dt, const Eigen::Vector3d& imu);
  void reset() { have_ = false; }

 private:
  Eigen::Vector2d lastAcceleration_ = Eigen::Vector2d::Zero(), lastLever_ = Eigen::Vector2d::Zero();
  bool have_ = false;
};

class InertialOdometry {
 public:
  struct Params {
    double processVelocity = 0.005;  // m/s per cycle: the prediction's error (accelerometer noise, model)
    double processBias = 0.002;      // m/s^2 per cycle: how fast the accelerometer's bias may drift
    double measurement = 0.02;       // m/s: a fully loaded foot's kinematic velocity scatter
    double gate = 3.0;               // standard deviations beyond which a foot's velocity is rejected
    double initialBias = 0.3;        // m/s^2, standard deviation of the bias at the start
  };

  InertialOdometry() : InertialOdometry(Params{}) {}
  explicit InertialOdometry(const Params& params) : params_(params) {}

  // Forget the state (the robot lay down, was lifted, or the odometry restarts).
  void reset() { initialised_ = false; }
  bool initialised() const { return initialised_; }

  // One cycle of dt seconds. turn: the robot frame's rotation from the last cycle's start to
  // this one's (rad); the state is carried into the new frame. imuDelta: the velocity change the IMU measured over the cycle
  // (m/s, robot frame at the cycle's start; gravity and lever arm taken out). Then the feet's
  // kinematic velocities (robot frame at the cycle's start) with their weights in [0, 1]; a
  // weight of 0 is no measurement. Returns the cycle's mean velocity estimate.
  Eigen::Vector2d update(double dt, double turn, const Eigen::Vector2d& imuDelta, const Eigen::Vector2d& leftVelocity,
                         double leftWeight, const Eigen::Vector2d& rightVelocity, double rightWeight);

  const Eigen::Vector2d& velocity() const { return velocity_; }
  const Eigen::Vector2d& bias() const { return bias_; }
  // How many foot measurements were rejected as moving since construction (logs, tests).
  int rejected() const { return rejected_; }

 private:
  // One foot's kinematic velocity; false when it is rejected (the foot moved).
  bool measure(const Eigen::Vector2d& z, double weight);

  Params params_;
  bool initialised_ = false;
  Eigen::Vector2d velocity_ = Eigen::Vector2d::Zero(), bias_ = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance_ = Eigen::Matrix2d::Zero();  // (velocity, bias), the same for x and y
  int rejected_ = 0, rejectedInARow_ = 0;
};

}  // namespace nao
