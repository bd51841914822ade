// nao-soccer render: one simulated camera image (or a top-down view of the field).
#include <mujoco/mujoco.h>

#include <cmath>
#include <optional>
#include <cstdio>
#include <iostream>
#include <random>


#include "apps/Cli.h"
#include "apps/Commands.h"
#include "apps/SampleReport.h"
#include "apps/SimOptions.h"
#include "controllers/StandController.h"
#include "perception/RecordedCameraMatrix.h"
#include "robot/Error.h"
#include "robot/ForwardKinematics.h"
#include "robot/Paths.h"
#include "scenarios/ProgramMetering.h"
#include "sim/CameraRenderer.h"
#include "sim/FieldView.h"
#include "sim/ImageIO.h"
#include "sim/World.h"

namespace nao::cli {

int renderCommand(const RenderOptions& o) {
  CameraId camera = o.camera == "top" ? CameraId::Top : CameraId::Bottom;
  const auto p = o.pose.empty() ? std::vector<double>{0, 0, 0} : o.pose;
  Eigen::Vector3d pose(p[0], p[1], p[2] * M_PI / 180);
  // The twin of a recorded real image: where its robot stood, from its goal-box labels.
  std::optional<RecordedCameraMatrix> recorded;
  Eigen::Vector3d twinPose = Eigen::Vector3d::Zero();
  if (!o.cameraMatrix.empty()) {
    recorded = RecordedCameraMatrix::read(o.cameraMatrix);
    camera = recordedCamera(*recorded, o.cameraMatrix, camera, o.common.has("--camera"));
    twinPose = recorded->robotPoseOnField(fieldFrom(o.common), o.cameraMatrix);
    // The simulated robot stands a metre behind its camera, out of the picture.
    pose = twinPose - Eigen::Vector3d(std::cos(twinPose.z()), std::sin(twinPose.z()), 0);
  }
  const auto h = o.head.empty() ? std::vector<double>{0, 0} : o.head;
  const sim::Lighting lighting = lightingFrom(o.sim.lighting);
  const std::uint32_t seed = o.common.seed;
  const CameraCalibration offsets = miscalibrationFrom(o.sim, seed);
  const std::string& out = o.out;

  sim::SceneSpec spec;
  spec.field = fieldFrom(o.common);
  spec.robotModel = o.sim.model;
  spec.venue = venueFrom(o.sim.venue).forSeed(seed);
  spec.venueSeed = seed;
  spec.robots = {pose};
  if (recorded) (camera == CameraId::Top ? spec.top : spec.bottom) = {RecordedCameraMatrix::kWidth, RecordedCameraMatrix::kHeight};
  if (!o.ball.empty()) spec.balls = {Eigen::Vector3d(o.ball[0], o.ball[1], 0.05)};
  sim::World world(spec, seed);
  world.setMiscalibration(0, offsets);
  JointArray posture = StandController::standPosture();
  posture[HeadYaw] = h[0] * M_PI / 180;
  posture[HeadPitch] = h[1] * M_PI / 180;
  world.placeRobot(0, pose, posture);
  if (recorded) {
    const Eigen::Isometry3d robotOnField =
        Eigen::Translation3d(twinPose.x(), twinPose.y(), 0) * Eigen::AngleAxisd(twinPose.z(), Eigen::Vector3d::UnitZ());
    world.placeCamera(0, camera, robotOnField * recorded->matrix.pose, recorded->matrix.intrinsics.fovY());
  }

  const sim::CameraResolution res = world.cameraResolution(camera);
  std::optional<sim::CameraExposure> exposure;
  if (o.view == "field") {
    std::vector<Eigen::Vector3d> balls;
    for (int b = 0; b < world.ballCount(); ++b) balls.push_back(world.ballPosition(b));
    sim::writePng(out, sim::drawFieldView(world.field(), {world.robotPose(0)}, balls));
  } else {
    sim::CameraRenderer renderer(world.model());
    std::mt19937_64 rng(seed);
    // Exposed as the robot program meters (its AutoExposureWeighting), with the camera it knows.
    const ProgramMetering metering(dataPath("config"));
    const SensorFrame sensors = world.sensors(0);
    const CameraIntrinsics in = CameraIntrinsics::fromFovY(res.width, res.height, world.cameraFovY());
    const ExposureWeights weights =
        recorded ? metering(recorded->matrix)
                 : metering(computeCameraMatrix(sensors.joints.position, sensors.inertial.angle, camera, offsets, in),
                            sensors, offsets);
    const CameraImage img = renderer.renderImage(world.model(), world.data(), world.cameraIndex(0, camera), res.width,
                                                 res.height, lighting, camera, world.time(), rng, weights);
    sim::writePng(out, img);
    exposure = renderer.cameraExposure(world.cameraIndex(0, camera));
  }

  if (!o.common.json.empty()) {
    const Eigen::Isometry3d cam = world.cameraPose(0, camera);
    const double fovY = world.cameraFovY();
    const double fovX = 2 * std::atan(res.width / (double)res.height * std::tan(fovY / 2));
    nlohmann::json rotation = nlohmann::json::array();
    for (int r = 0; r < 3; ++r) rotation.push_back({cam.linear()(r, 0), cam.linear()(r, 1), cam.linear()(r, 2)});
    const Eigen::Vector3d truePose = world.robotPose(0);
    nlohmann::json j = {
        {"camera",
         {{"name", o.camera},
          {"width", res.width},
          {"height", res.height},
          {"fov_x_deg", fovX * 180 / M_PI},
          {"fov_y_deg", fovY * 180 / M_PI},
          {"position", {cam.translation().x(), cam.translation().y(), cam.translation().z()}},
          {"rotation", rotation}}},
        {"robot", {{"pose", {truePose.x(), truePose.y(), truePose.z() * 180 / M_PI}}}},
        {"twin", recorded ? nlohmann::json{{"camera_matrix", o.cameraMatrix},
                                           {"robot_pose", {twinPose.x(), twinPose.y(), twinPose.z() * 180 / M_PI}}}
                          : nlohmann::json(nullptr)},
        {"head", {h[0], h[1]}},
        {"miscalibration_deg", calibrationDegJson(offsets)},
        {"lighting", lightingJson(lighting)},
        {"venue", sim::toJson(spec.venue)},
        {"camera_exposure", exposure ? cameraExposureJson(*exposure) : nlohmann::json(nullptr)},
        {"view", o.view},
        {"out", out},
        {"seed", seed}};
    writeJson(o.common.json, j);
  }
  return 0;
}

}  // namespace nao::cli
