// The robot program sees: in the simulator, every camera image runs through the robot
// program's own cognition (ExposureCameraMatrixProvider, CameraVision with both cameras'
// CameraPipeline), and the field lines it reports lie on the field's real lines, judged by the
// simulator's truth (the robot's true pose and the field model), not by anything the program
// computed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>

#include "controllers/RobotProgram.h"
#include "controllers/StandController.h"
#include "perception/FieldDimensions.h"
#include "representations/perception/CameraPercepts.h"
#include "robot/Paths.h"
#include "scenarios/SimRun.h"
#include "sim/CameraRenderer.h"
#include "sim/Lighting.h"
#include "sim/SimBackend.h"
#include "sim/World.h"

namespace nao {
namespace {

double distanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

TEST(Cognition, TheRobotProgramSeesTheFieldLinesWhereTheyAre) {
  const FieldDimensions field = FieldDimensions::load(dataPath("config/field_dimensions.json"));
  const FieldModel model = FieldModel::from(field);
  sim::SceneSpec spec;
  spec.field = field;
  const Eigen::Vector3d pose(-3.2, -3.0, M_PI / 2);  // on the side line, facing the field
  spec.robots = {pose};
  sim::World world(spec, 3);
  world.placeRobot(0, pose, StandController::standPosture());
  sim::SimBackend backend(world, 0, true);
  sim::CameraRenderer renderer(world.model());
  std::mt19937_64 rng(3);
  const sim::Lighting lighting = sim::Lighting::parse("default", dataPath("config/lighting.json"));
  backend.setImageSource([&](CameraId cam, double time, const ExposureWeights& metering) {
    const sim::CameraResolution res = world.cameraResolution(cam);
    return renderer.renderImage(world.model(), world.data(), world.cameraIndex(0, cam), res.width, res.height,
                                lighting, cam, time, rng, metering);
  });
  RobotProgramConfig config;
  config.field = field;
  config.withoutBehavior();  // the head still: what the vision sees, not where the head looks
  RobotProgram program(config);

  int perceptSets = 0, lines = 0, offLines = 0;
  long runs = 0;
  for (int c = 0; c < 125; ++c) {  // 1.5 s
    ASSERT_TRUE(program.cycle(backend));
    const long now = program.cognitionRuns()[0] + program.cognitionRuns()[1];
    if (now == runs) continue;
    runs = now;
    const CameraPercepts& p = program.cognitionBoard().read<CameraPercepts>();
    ++perceptSets;
    const Eigen::Vector3d truth = world.robotPose(0);
    const Eigen::Rotation2Dd r(truth.z());
    for (const auto& l : p.lines) {
      ++lines;
      for (const Eigen::Vector2d& end : {l.from, l.to}) {
        const Eigen::Vector2d f = r * end + truth.head<2>();
        double best = 1e9;
        for (const auto& fl : model.lines) best = std::min(best, distanceToSegment(f, fl.from, fl.to));
        if (best > 0.15) ++offLines;
      }
    }
  }
  std::printf("cognition: %ld top + %ld bottom images, %d lines, %d of %d line ends off the field's lines\n",
              program.cognitionRuns()[0], program.cognitionRuns()[1], lines, offLines, 2 * lines);
  // 30 Hz per camera for 1.5 s, less the first frames before the robot program's first cycle.
  EXPECT_GE(program.cognitionRuns()[0], 40);
  EXPECT_GE(program.cognitionRuns()[1], 40);
  EXPECT_GE(perceptSets, 40);
  EXPECT_GT(lines, 40) << "the robot program saw hardly any lines";
  // Where each camera meters (AutoExposureWeighting) went from the program to the backend, which
  // renders with it: looking across the field from the side line, the top camera's upper cells
  // see the hall beyond the far side line, its lower ones the near field.
  const ExposureWeights& top = backend.exposureWeights(CameraId::Top);
  EXPECT_FALSE(top.uniform());
  EXPECT_EQ(top.at(0, 0), 0);
  EXPECT_EQ(top.at(0, 3), 0);
  EXPECT_EQ(top.at(3, 1), 15);
  EXPECT_EQ(top.at(3, 2), 15);
  EXPECT_LE(offLines, lines / 20) << offLines << " of " << 2 * lines << " line ends off every field line";
}

// The acceptance's walk in small: the robot program walks from the side line to a commanded
// pose by its own localization (the behaviour never sees the truth); the simulator's truth
// says where it ended. Cameras at 30 Hz each, all of it in the robot program's cognition.
TEST(Cognition, TheRobotProgramWalksToACommandedPoseByItsOwnLocalization) {
  sim::SimRunOptions o;
  o.field = FieldDimensions::load(dataPath("config/field_dimensions.json"));
  o.pose = Eigen::Vector3d(-3.2, -3.0, M_PI / 2);
  o.seconds = 22;
  o.goTo = Pose2(-1.8, -1.6, 0);
  o.ball = Eigen::Vector2d(-2.2, -1.0);
  o.seed = 5;
  o.lighting = sim::Lighting::parse("default", dataPath("config/lighting.json"));
  const sim::SimRunResult r = sim::runSim(o);
  ASSERT_FALSE(r.fell);
  const double position = (r.finalPose.head<2>() - Eigen::Vector2d(o.goTo->x, o.goTo->y)).norm();
  const double heading = std::abs(Pose2::wrap(r.finalPose.z() - o.goTo->theta));
  std::printf("goto: ended %.3f m and %.2f deg from the target; localization error median %.3f m over %zu images; "
              "ball error median %.3f m over %zu\n",
              position, heading * 180 / M_PI, sim::median(r.positionErrors), r.positionErrors.size(),
              sim::median(r.ballErrors), r.ballErrors.size());
  EXPECT_LT(position, 0.10);
  EXPECT_LT(heading, 5 * M_PI / 180);
  // Localized nearly all the time, and close (the robot walked 1.9 m and turned 90 degrees).
  EXPECT_GT(r.validRuns, r.cognitionRunsTotal * 8 / 10);
  EXPECT_LT(sim::median(r.positionErrors), 0.05);
  EXPECT_LT(sim::median(r.headingErrors), 2 * M_PI / 180);
  // The ball on its way was seen and modelled where it is (robot frame, against the truth).
  ASSERT_GT(r.ballErrors.size(), 30u);
  EXPECT_LT(sim::median(r.ballErrors), 0.10);
  // Both cameras at 30 Hz through the cognition.
  EXPECT_GE(r.imagesProcessedTop, static_cast<long>(29.5 * o.seconds));
  EXPECT_GE(r.imagesProcessedBottom, static_cast<long>(29.5 * o.seconds));
}

}  // namespace
}  // namespace nao
