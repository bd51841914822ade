#pragma once
// The simulated world: one MuJoCo model with the field, robots and balls, stepped at a fixed
// physics step. Each robot's joints follow its JointRequest through a NAO servo model (position
// control with stiffness, torque and speed limits). Sensors are simulated from the state; the
// injected miscalibration lives here (the hardware), never in the robot program.
// Ground truth is for scenarios and tests only.
#include <array>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "perception/CameraCalibration.h"
#include "perception/FieldDimensions.h"
#include "robot/CameraImage.h"
#include "robot/JointRequest.h"
#include "robot/SensorData.h"
#include "sim/SceneSpec.h"

struct mjModel_;
struct mjData_;

namespace nao::sim {

struct SensorNoise {
  double gyro = 0.0;   // rad/s std. dev.
  double accel = 0.0;  // m/s^2
  double angle = 0.0;  // rad, on the IMU's roll/pitch
  double joint = 0.0;  // rad, on joint position readings
};

class World {
 public:
  explicit World(const SceneSpec& spec, std::uint64_t seed = 0);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  mjModel_* model();
  mjData_* data();
  const mjModel_* model() const;
  const mjData_* data() const;
  const SceneSpec& spec() const;
  const FieldModel& field() const;
  int robotCount() const;
  int ballCount() const;
  double time() const;

  // Physics: one fixed step, or one 12 ms robot cycle (several steps). Throws nao::Error
  // ("simulation", "NaN in ...") when the state stops being finite.
  void step();
  void stepCycle();

  // The robot program's side of the hardware.
  void setJointRequest(int robot, const JointRequest& request);
  SensorFrame sensors(int robot) const;
  void setSensorNoise(const SensorNoise& noise);
  // Touch sensors (buttons, bumpers) read 0 unless a test or scenario presses one.
  void setTouch(int robot, Touch touch, double value);

  // Injected miscalibration (the hardware's true offsets), rad.
  void setMiscalibration(int robot, const CameraCalibration& offsets);
  CameraCalibration miscalibration(int robot) const;

  // Places a robot standing at (x, y, theta) with the given joint angles (LoLA order), feet on
  // the carpet, at rest; its servo targets become those angles at full stiffness.
  void placeRobot(int robot, const Eigen::Vector3d& pose, const JointArray& posture);
  void placeBall(int ball, const Eigen::Vector3d& position, const Eigen::Vector3d& velocity = Eigen::Vector3d::Zero());
  // Adds a linear impulse (N s, field frame) to the torso.
  void pushRobot(int robot, const Eigen::Vector3d& impulse);

  // Variation of the simulated hardware ("foreign robots"); the nominal robot until set.
  // Joint calibration offsets (rad): the true joint angle is the reading plus the offset, so the
  // servo holds target + offset and the sensor reports the angle minus the offset.
  void setJointOffsets(int robot, const JointArray& offsets);
  JointArray jointOffsets(int robot) const;
  // Scales each body's mass and inertia of the robot by its own factor drawn uniformly from
  // [1 - spread, 1 + spread] (spread in [0, 0.5]); returns the robot's new total mass (kg).
  double scaleLinkMasses(int robot, double spread, std::uint64_t seed);
  // Sliding friction of the feet on the carpet (and of the carpet for everything else).
  void setFloorFriction(double friction);
  // The colour (RGBA, 0..1) of the robot's geom named `geom` (without its prefix): a team's
  // jersey on "torso_geom". False when the robot's model has no such geom.
  bool setGeomColour(int robot, const std::string& geom, const Eigen::Vector4d& rgba);
  // Detaches the robot's camera from its head and fixes it at `fieldPose` (B-Human camera axes,
  // field frame) with vertical field of view fovY (rad): the simulated twin of a recorded real
  // image (render --camera-matrix). The robot's own pictures are meaningless afterwards.
  void placeCamera(int robot, CameraId camera, const Eigen::Isometry3d& fieldPose, double fovY);

  // Ground truth.
  Eigen::Vector3d robotPose(int robot) const;            // (x, y, theta), docs/conventions.md
  Eigen::Isometry3d torsoPose(int robot) const;          // torso frame in the field frame
  Eigen::Isometry3d cameraPose(int robot, CameraId camera) const;  // B-Human camera axes, field frame
  int cameraIndex(int robot, CameraId camera) const;     // MuJoCo camera id
  CameraResolution cameraResolution(CameraId camera) const;
  double cameraFovY() const;                             // rad
  Eigen::Vector3d ballPosition(int ball) const;
  Eigen::Vector3d ballVelocity(int ball) const;
  Eigen::Vector3d handPosition(int robot, bool left) const;  // the hand body's origin (the wrist), field frame
  // The four bottom corners of each sole's box (left foot's, then the right's), field frame.
  std::array<Eigen::Vector3d, 8> soleCorners(int robot) const;
  // A robot touched a ball: every touch that began since the last call (checked in every
  // physics step, so a touch shorter than a robot cycle counts), oldest first.
  struct BallContact {
    int robot = 0, ball = 0;
    double time = 0;  // s, simulated
  };
  std::vector<BallContact> takeBallContacts();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace nao::sim
