// nao-soccer render: one simulated camera image (or a top-down view of the field).
#include <mujoco/mujoco.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <random>

#include <opencv2/imgcodecs.hpp>

#include "apps/Commands.h"
#include "apps/SimOptions.h"
#include "controllers/StandController.h"
#include "robot/Error.h"
#include "sim/CameraRenderer.h"
#include "sim/FieldView.h"
#include "sim/ImageIO.h"
#include "sim/World.h"

namespace nao::cli {

int renderCommand(const Argv& argv) {
  auto options = commonOptions();
  for (auto& o : simOptions()) options.push_back(o);
  options.insert(options.end(),
                 {{"camera", "top|bottom", "which camera (default top)"},
                  {"view", "camera|field", "a camera image (default) or a top-down view of the field"},
                  {"pose", "X,Y,THETA", "robot pose: m, m, deg (default 0,0,0)"},
                  {"head", "YAW,PITCH", "head angles in deg (default 0,0)"},
                  {"ball", "X,Y", "a ball on the field at X,Y m"},
                  {"out", "FILE.png", "where to write the image (required)"}});
  Args args("render", argv, options);
  if (args.helpRequested()) {
    std::cout << args.usage();
    return 0;
  }
  const std::string out = args.str("out", "");
  if (out.empty()) throw Error("--out", "is required");
  const std::string cameraName = args.str("camera", "top");
  if (cameraName != "top" && cameraName != "bottom") throw Error("--camera", "must be top or bottom, not '" + cameraName + "'");
  const CameraId camera = cameraName == "top" ? CameraId::Top : CameraId::Bottom;
  const std::string view = args.str("view", "camera");
  if (view != "camera" && view != "field") throw Error("--view", "must be camera or field, not '" + view + "'");
  const auto p = args.optionalList("pose", 3).value_or(std::vector<double>{0, 0, 0});
  const Eigen::Vector3d pose(p[0], p[1], p[2] * M_PI / 180);
  const auto h = args.optionalList("head", 2).value_or(std::vector<double>{0, 0});
  const sim::Lighting lighting = lightingFrom(args);
  const CameraCalibration offsets = miscalibrationFrom(args, args.seed());

  sim::SceneSpec spec;
  spec.field = fieldFrom(args);
  spec.robotModel = robotModelFrom(args);
  spec.robots = {pose};
  if (auto b = args.optionalList("ball", 2)) spec.balls = {Eigen::Vector3d((*b)[0], (*b)[1], 0.05)};
  sim::World world(spec, args.seed());
  world.setMiscalibration(0, offsets);
  JointArray posture = StandController::standPosture();
  posture[HeadYaw] = h[0] * M_PI / 180;
  posture[HeadPitch] = h[1] * M_PI / 180;
  world.placeRobot(0, pose, posture);

  const sim::CameraResolution res = world.cameraResolution(camera);
  if (view == "field") {
    std::vector<Eigen::Vector3d> balls;
    for (int b = 0; b < world.ballCount(); ++b) balls.push_back(world.ballPosition(b));
    sim::writePng(out, sim::drawFieldView(world.field(), {world.robotPose(0)}, balls));
  } else {
    sim::CameraRenderer renderer(world.model());
    std::mt19937_64 rng(args.seed());
    const CameraImage img = renderer.renderImage(world.model(), world.data(), world.cameraIndex(0, camera), res.width,
                                                 res.height, lighting, camera, world.time(), rng);
    sim::writePng(out, img);
  }

  if (args.has("json")) {
    const Eigen::Isometry3d cam = world.cameraPose(0, camera);
    const double fovY = world.cameraFovY();
    const double fovX = 2 * std::atan(res.width / (double)res.height * std::tan(fovY / 2));
    nlohmann::json rotation = nlohmann::json::array();
    for (int r = 0; r < 3; ++r) rotation.push_back({cam.linear()(r, 0), cam.linear()(r, 1), cam.linear()(r, 2)});
    const Eigen::Vector3d truePose = world.robotPose(0);
    nlohmann::json j = {
        {"camera",
         {{"name", cameraName},
          {"width", res.width},
          {"height", res.height},
          {"fov_x_deg", fovX * 180 / M_PI},
          {"fov_y_deg", fovY * 180 / M_PI},
          {"position", {cam.translation().x(), cam.translation().y(), cam.translation().z()}},
          {"rotation", rotation}}},
        {"robot", {{"pose", {truePose.x(), truePose.y(), truePose.z() * 180 / M_PI}}}},
        {"head", {h[0], h[1]}},
        {"miscalibration_deg", calibrationDegJson(offsets)},
        {"lighting", lightingJson(lighting)},
        {"view", view},
        {"out", out},
        {"seed", args.seed()}};
    writeJson(args.str("json", "-"), j);
  }
  return 0;
}

}  // namespace nao::cli
