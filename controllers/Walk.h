#pragma once
// Omnidirectional walk for the NAO V6: a linear inverted pendulum (LIPM) gait whose footsteps
// are placed by the divergent component of motion (DCM, the "capture point"), stabilised on the
// body by the IMU (gyro and tilt) and weighted by the FSRs.
//
// Why this design. The NAO's servos are position controlled and weak (8.9 Nm stall at the
// knee), so the gait must not ask for more than gravity and the pendulum give: the centre of
// mass (COM) follows the LIPM with the zero-moment point (ZMP) fixed in the support foot, which
// keeps the soles flat and the ankle torques small, at any speed up to the servo's joint speed.
// Of the LIPM's two components only the DCM xi = c + c'/omega diverges (xi' = omega (xi - p));
// the COM converges to it by itself. So balance is a matter of where the next foot lands:
// during each step the DCM at touch-down is predicted, xi_end = p + (xi - p) e^(omega (T - t)),
// and the swing foot is sent to xi_end - b, where b is the DCM's offset from the landing foot
// in the periodic gait for the commanded speed (found by the backward recursion over the next
// few nominal footsteps). That makes every speed change and every start and stop a planned
// DCM transition inside the leg's reach (step adjustment, as in the capture-point literature
// and B-Human's walk). Compared with ZMP preview control this needs no preview horizon of
// future ZMPs and reacts within one step; compared with a purely reactive walk (B-Human 2018)
// the sway is planned, so fast steps need no luck with the rocking phase.
//
// Closed loop, and what was measured (eval walk: random commands every 2-5 s, 60 s trials):
//  - gyro damping: the support ankle's pitch and roll targets get a share of the filtered body
//    rate -- the fast part of a disturbance (a foot landing hard, a toe catching) is damped by
//    the ankle before it tips the body;
//  - the swing sole is kept parallel to the ground and placed relative to the support sole in
//    the world (not the torso), undoing the IMU's measured tilt beyond the planned one; the
//    landed foot keeps that correction and lets it decay, so nothing jumps;
//  - heading: the gyro's yaw beyond the commanded turn (feet slipping about the vertical) is
//    turned back over the next steps;
//  - the support legs' sag under load is compensated with the weight share the FSRs measure;
//  - the measured COM (support sole -> joint encoders -> IMU tilt) is compared with the model
//    every cycle (state().comError) for tests and logs.
// Tried and measured worse, hence not used: feeding the measured COM/DCM error into the step
// adjustment or into the model state (the footsteps then follow the body's sway within a step,
// the model's own DCM leaves the periodic gait and the next steps run into the reach limits:
// pushed at 0.2 m/s with 3 N s, 2-8 of 8 directions fell against 1 of 8 without), and ending a
// step early when the swing foot's FSRs already carry weight (the plan's timing then differs
// from the model's and the following steps saturated at the leg's reach: 2 falls in 20
// randomised random-command trials against 0 with touch-down on time). The swing foot's
// clearance mattered most: 3.5 cm instead of 2.5 (a toe catching the carpet at fast combined
// speeds was the first event of most falls) took the random-command trials from 3 falls in 20
// to none; with both changes 100 trials of 60 s (seeds 1-3, nominal and randomised) had none.
// Odometry: the robot frame's motion relative to where the loaded sole(s) touch the ground,
// from the measured joint angles and the IMU's tilt (translation, each foot weighted by its FSR
// load) and the gyro (rotation: the torso's attitude carried on by the gyro from the IMU's
// tilt, its change of heading; the Euler yaw rate overstated turns by 0.12 %). The ground
// contact is the FSRs' centre of pressure, moved out to the sole's edge when one edge carries
// the weight (a foot rolling onto its toes turns about that edge, not about the point below
// the ankle). A foot the walk has begun to lift counts no more, whatever its FSRs read: traced
// against the truth, a late landing left the weight on the foot being dragged off and the
// odometry ran 8 mm a cycle the wrong way. A sole that twists on the floor (the gyro turns
// more than the leg) carries the robot frame about its contact. Each foot's velocity is then
// checked against the IMU's prediction (InertialOdometry.h): a landing foot still sliding or
// bouncing in the air is rejected for the cycle. Measured on randomised 3 m walk-to trials
// (480, seeds 1-24) against the kinematics alone: the odometry's error across the path 0.9 cm
// rms instead of 2.1; the robot's final error median 1.3 cm instead of 2.2, the worst 4.0 cm
// instead of 27 (6 trials over 5 cm before, none now).
// Joint offsets (a "foreign" robot, +-1 deg per joint) tilt the soles: a sole pitched by 1 deg
// lands on its toe or heel and slips; with the legs' errors opposed the randomised robot turned
// 100 deg in 8 s walking "straight" and walk-to missed by up to 25 cm. Standing, the floor holds
// both soles flat, so their roll and pitch measured through the (offset) joint angles and the
// IMU are the legs' errors; the IK targets turn them back (sole levelling). What the odometry
// still misses is the feet creeping steadily (neither kinematics nor IMU can see a constant
// slip); its mean along the path is taken out by odometryScale.
#include <array>

#include <Eigen/Geometry>

#include "controllers/InertialOdometry.h"
#include "representations/behavior/MotionRequest.h"
#include "robot/Debug.h"
#include "robot/JointRequest.h"
#include "robot/SensorData.h"

namespace nao {

class Walk {
 public:
  struct Params {
    double stepDuration = 0.25;   // s, one single-support phase
    double stepHeight = 0.035;    // m, swing foot clearance at mid-step
    double torsoHeight = 0.222;   // m, torso origin above the ground
    double torsoPitch = 0.0;      // rad, forward lean of the torso
    double footSpacing = 0.10;    // m, between the sole centres standing
    double zmpX = 0.012;          // m, the ZMP in the support sole, forward of the ankle
    double zmpYInside = 0.008;    // m, the ZMP towards the inner edge
    double zmpTravelX = 0.6;      // share of the COM's travel over the sole the ZMP follows (heel to toe)
    double zmpTravelY = 0.3;      // ... sideways
    double maxZmpTravelX = 0.05;  // m
    double maxZmpTravelY = 0.015; // m
    double maxForward = 0.36;     // m/s
    double maxBackward = 0.22;    // m/s
    double maxSide = 0.2;         // m/s
    double maxTurn = 1.5;         // rad/s
    double accelForward = 0.5;    // m/s^2 of the applied speed (per step)
    double accelSide = 0.6;       // m/s^2
    double accelTurn = 3.0;       // rad/s^2
    double maxStepOutward = 0.13;  // m, lateral reach beyond the standing spacing
    double maxStepInward = 0.015;  // m, inside the standing spacing
    double maxStepForward = 0.11;  // m, swing foot ahead of the support foot
    double maxStepBackward = 0.08;
    double startDuration = 0.3;   // s of double support to shift the DCM onto the first support foot
    double gyroPitchGain = 0.1;   // rad per rad/s, support ankle pitch
    double gyroRollGain = 0.05;   // rad per rad/s, support ankle roll
    double adjustUntilPhase = 0.75;    // the swing target follows the DCM until this fraction
    // Sag compensation: the leg servos' position gain (N m / rad) as the robot program knows
    // it; the support legs' joint targets get tau / gain for the torques that carry the robot.
    double servoGain = 60.0;
    double headingGain = 0.5;            // per step: share of the gyro's heading error turned back
    double maxHeadingCorrection = 0.08;  // rad per step
    bool gyroOdometry = true;
    double odometryLoadExponent = 2.0;  // the feet's odometry weights: (FSR load share)^exponent
    // Translation increments' factor. The feet still creep a little at the weight transfers
    // (more on a slippery floor), which neither the kinematics nor the IMU can see. Measured with
    // the inertial, twist-aware odometry (240 randomised 3 m walk-to trials, friction 0.6-1.0,
    // seeds 1-12): 1.004 leaves no mean error along the path (0.0 cm; seeds 13-24: -0.06 cm).
    double odometryScale = 1.004;
    // The same for the kinematics alone (the IMU's check off: no plausible accelerometer), where
    // the rejected cycles' slips count too: 1.006 (120 randomised trials, seeds 1-6).
    double kinematicOdometryScale = 1.006;
    // A loaded sole's twist (gyro turn beyond the leg's) turns the robot frame about the sole's
    // ground contact, not about the robot frame's origin.
    bool twistAboutContact = true;
    // The feet's velocities checked against the IMU's (InertialOdometry.h); off: the feet's
    // motions blended by their load alone.
    bool inertialOdometry = true;
    InertialOdometry::Params inertial;
    double odometrySwingAfter = 0.036;  // s into a step after which the swing foot counts no more
    double sagCompensation = 1.0;  // 0 = off
    double leadTime = 0.0;   // s: swing leg targets lead the trajectory (the servos' kd / kp)
    double supportLeadTime = 0.0;  // s: the same for the support leg
    double swingTiltCompensation = 1.0;   // 0 = off: swing sole parallel to the ground
    double landingCorrectionDecay = 0.06;  // s, how fast a landed foot returns to the plan
    // Sole levelling: standing on both feet, each sole's roll and pitch as the measured joint
    // angles and the IMU see it (the floor holds both soles flat, so what is not level is the
    // leg's joint calibration error) is averaged and turned back in every later IK target.
    bool levelSoles = true;
    double levelTime = 0.3;       // s, the estimate's time constant
    double maxLevelCorrection = 0.07;  // rad per axis
    double maxLevelRate = 0.4;         // rad/s: how fast the applied correction may change
  };

  enum class Phase { Standing, Starting, Walking, Stopping };

  Walk() : Walk(Params{}) {}
  explicit Walk(const Params& params);

  // The walk's standing posture: feet at footSpacing, COM above their midpoint, torso at
  // torsoHeight (the walk starts and ends there). Arms hang at the sides.
  JointArray standPosture() const;

  // The channels walk_trace goes to (not owned; null: none).
  void setDebug(DebugChannels* debug) { debug_ = debug ? debug : &DebugChannels::none(); }

  // Starts from the stand posture: resets the model to the measured state.
  void reset(const SensorFrame& frame);
  // One cycle. speed: vx, vy, vtheta (robot frame, clipped to the limits). With a zero speed and
  // stop set, the walk closes its feet and comes to a stand.
  JointRequest update(const SensorFrame& frame, const Pose2& speed, bool stop = false);

  // Odometry, once per cycle whatever the robot does: translation from the support sole's
  // kinematics unless rotationOnly (lying, getting up), rotation from the gyro.
  void updateOdometry(const SensorFrame& frame, bool rotationOnly = false);
  void resetOdometry(const Pose2& pose = {}) { odometry_ = pose; haveRelative_ = false; }

  Phase phase() const { return phase_; }
  bool standing() const { return phase_ == Phase::Standing; }
  const Pose2& odometry() const { return odometry_; }
  // Where the robot frame would be (odometry frame) once the robot stands on its feet as they
  // are now: the feet's centre (from the legs' kinematics) and the stand posture's offset of the
  // robot frame from it. Free of the body's sway within a step; WalkTo stops on it.
  const Pose2& standPoseEstimate() const { return standPoseEstimate_; }
  // Where the robot frame would be once the walk stopped at the next chance: the swing foot
  // landed where the plan sends it, the other foot closed beside it (the feet's centre as in
  // standPoseEstimate otherwise). WalkTo steers by it: it already holds the step in the air.
  const Pose2& stopPoseEstimate() const { return stopPoseEstimate_; }
  const Pose2& appliedSpeed() const { return speed_; }
  const Params& params() const { return params_; }
  Params& params() { return params_; }
  // The soles' roll and pitch (rad) the levelling turns back: [left, right] x (roll, pitch).
  Eigen::Vector2d soleLevel(bool left) const { return level_[left ? 0 : 1]; }
  int steps() const { return steps_; }
  // The model's state in the walk's plan frame (for tests and logs).
  struct State {
    Eigen::Vector2d com, comVelocity, zmp;
    Pose2 left, right, swingTarget;
    bool supportLeft = false;
    double stepTime = 0;
    Eigen::Vector2d comError, comErrorRate;  // measured COM - model COM and its rate (Walking only)
  };
  State state() const { return {c_, cd_, zmp_, left_, right_, swingTarget_, supportLeft_, t_, comError_, comErrorRate_}; }
  // The largest speeds the walk accepts, per axis (vx forward, vy, vtheta).
  Pose2 clipSpeed(const Pose2& speed) const;

 private:
  struct Foot3 {
    Pose2 pose;
    double z = 0;
  };

  Eigen::Vector2d zmpOf(const Pose2& foot, bool left) const;
  Pose2 nominalTarget(const Pose2& support, bool swingLeft, const Pose2& speed) const;
  Pose2 clipTarget(const Pose2& support, bool swingLeft, const Pose2& target) const;
  struct StepZmp {
    Eigen::Vector2d p0, p1;  // the ZMP at the step's start and end
  };
  StepZmp stepZmp(const Pose2& support, bool supportLeft, const Pose2& from, const Pose2& to) const;
  Eigen::Vector2d zmpAt(const StepZmp& z, double t) const;
  Eigen::Vector2d dcmAtStart(const StepZmp& z, const Eigen::Vector2d& xiEnd) const;
  Eigen::Vector2d dcmAtEnd(const StepZmp& z, const Eigen::Vector2d& xi, double t) const;
  Eigen::Vector2d periodicOffset(const Pose2& support, bool supportLeft, const Pose2& target) const;
  void startStep(double time);
  void updateSpeed(const Pose2& request);
  void integrateModel(const Eigen::Vector2d& zmp, double dt);
  void measureState(const SensorFrame& frame, double dt);
  JointArray solve(const Foot3& left, const Foot3& right, double torsoYaw, const Eigen::Matrix3d& leftCorrection,
                   const Eigen::Matrix3d& rightCorrection, int swingSide);
  void estimateLevel(const SensorFrame& frame, double dt);
  void compensateSag(JointArray& joints, const Foot3& left, const Foot3& right, double leftShare) const;
  bool closedFeet() const;

  Params params_;
  DebugChannels* debug_ = &DebugChannels::none();
  double omega_ = 6.0;      // sqrt(g / COM height)
  double comHeight_ = 0.26;
  Phase phase_ = Phase::Standing;
  bool supportLeft_ = false;
  double t_ = 0, stepDuration_ = 0.25;
  double lastTime_ = -1;
  Pose2 support_, swingStart_, swingTarget_;  // the walk's plan frame
  Pose2 left_, right_;                        // where the feet are (plan frame)
  Eigen::Vector2d c_ = Eigen::Vector2d::Zero(), cd_ = Eigen::Vector2d::Zero();  // model COM
  Eigen::Vector2d zmp_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d comError_ = Eigen::Vector2d::Zero(), comErrorRate_ = Eigen::Vector2d::Zero();
  bool haveMeasurement_ = false, measuredLeft_ = false;
  Eigen::Vector2d torsoXY_ = Eigen::Vector2d::Zero();
  Eigen::Isometry3d torso_ = Eigen::Isometry3d::Identity();  // plan frame
  Pose2 speed_;
  bool stopRequested_ = false;
  int steps_ = 0;
  // Odometry.
  Pose2 odometry_;
  Pose2 standPoseEstimate_, stopPoseEstimate_;
  Pose2 standOffset_;  // the robot frame in the feet's centre frame, standing
  std::array<Eigen::Isometry3d, 2> lastSoles_{};  // left / right sole in the torso's yaw-free frame, last cycle
  bool haveRelative_ = false;
  double odometryLeftShare_ = 0.5;
  double odometryTime_ = -1;
  InertialOdometry inertial_;
  ImuVelocityChange imuVelocity_;
  double lastTurn_ = 0;  // rad, the last cycle's turn (the inertial state's frame change)
  double gravityReading_ = 0;  // m/s^2, the accelerometer's upward reading, low-passed
  Eigen::Matrix3d lastTilt_ = Eigen::Matrix3d::Identity();
  double leftShare_ = 0.5;
  double yawError_ = 0, headingCorrection_ = 0;
  Eigen::Vector2d gyroFiltered_ = Eigen::Vector2d::Zero();
  JointArray lastCommand_{};
  JointArray arms_{};
  JointArray previousIK_{};
  bool havePreviousIK_ = false;  // the stand posture: arms and head
  Eigen::Vector3d swingCorrection_ = Eigen::Vector3d::Zero(), landCorrection_ = Eigen::Vector3d::Zero();
  bool landedLeft_ = true;
  double landTime_ = -1e9;
  std::array<Eigen::Vector2d, 2> level_{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};  // [left, right] (roll, pitch)
  double levelWeight_ = 0;  // seconds of standing averaged so far (capped)
};

}  // namespace nao
