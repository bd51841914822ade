// The calibration challenge's phase 1 done by the robot program itself (issue 20): a robot with
// injected camera offsets, placed at the challenge's start, gets the referee's chest + head
// front; it localizes, walks to its own goal box's side, takes the views, solves, applies and
// reports. Judged against the simulator's truth: the injected offsets, the path it walked, the
// arm it raised. Nothing here moves the robot after the start.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "controllers/RobotProgram.h"
#include "controllers/StandController.h"
#include "perception/FieldDimensions.h"
#include "perception/calibration/CalibrationViews.h"
#include "representations/behavior/CalibrationRequest.h"
#include "representations/behavior/SpeechRequest.h"
#include "representations/modeling/RobotPose.h"
#include "representations/infrastructure/ChallengeMode.h"
#include "representations/perception/CalibrationStatus.h"
#include "robot/Paths.h"
#include "sim/CameraRenderer.h"
#include "sim/SimBackend.h"
#include "sim/World.h"

namespace nao {
namespace {

constexpr double kDeg = M_PI / 180;

struct Phase1 {
  bool finished = false;
  double simSeconds = 0;
  CameraCalibration applied;
  int appliedId = 0;
  std::array<int, 2> samples{};
  double maxStep = 0, pathLength = 0;
  bool armUpAtSpeech = false;
  bool fell = false;
  double maxTiltDeg = 0;
  std::string calibrateState;
};

Phase1 runPhase1(const CameraCalibration& injected, int sideSign, std::uint64_t seed, double limit) {
  const FieldDimensions field = FieldDimensions::load(dataPath("config/field_dimensions.json"));
  sim::SceneSpec spec;
  spec.field = field;
  const Eigen::Vector3d start = calibration::initialPosition(field, sideSign);
  spec.robots = {start};
  sim::World world(spec, seed);
  world.setMiscalibration(0, injected);
  world.placeRobot(0, start, StandController::standPosture());
  sim::SimBackend backend(world, 0, true);
  sim::CameraRenderer renderer(world.model());
  std::mt19937_64 noise(seed);
  sim::Lighting lighting;
  backend.setImageSource([&](CameraId cam, double time) {
    const sim::CameraResolution res = world.cameraResolution(cam);
    return renderer.renderImage(world.model(), world.data(), world.cameraIndex(0, cam), res.width, res.height, lighting,
                                cam, time, noise);
  });
  RobotProgramConfig config;
  config.field = field;
  RobotProgram program(config);
  const Blackboard& bb = program.blackboard();
  Phase1 r;
  auto cycle = [&] {
    const Eigen::Vector3d before = world.robotPose(0);
    if (!program.cycle(backend)) return false;
    const Eigen::Vector3d after = world.robotPose(0);
    r.maxStep = std::max(r.maxStep, (after.head<2>() - before.head<2>()).norm());
    r.pathLength += (after.head<2>() - before.head<2>()).norm();
    const Eigen::Isometry3d torso = world.torsoPose(0);
    r.maxTiltDeg = std::max(r.maxTiltDeg, std::acos(std::clamp(torso.linear()(2, 2), -1.0, 1.0)) / kDeg);
    if (r.maxTiltDeg > 45 || torso.translation().z() < 0.15) r.fell = true;
    return true;
  };
  for (double t = 0; t < 1.0; t += 0.012) EXPECT_TRUE(cycle());
  world.setTouch(0, ChestButton, 1.0);
  world.setTouch(0, HeadFront, 1.0);
  for (double t = 0; t < 1.2; t += 0.012) EXPECT_TRUE(cycle());
  world.setTouch(0, ChestButton, 0.0);
  world.setTouch(0, HeadFront, 0.0);
  const double t0 = bb.read<ChallengeMode>().since;
  int lastSpeech = bb.read<SpeechRequest>().id;
  while (world.time() - t0 < limit) {
    if (!cycle()) break;
    if (std::getenv("NAO_TEST_VERBOSE") && static_cast<long>(world.time() / 0.012) % 84 == 0) {
      const Blackboard& c = program.cognitionBoard();
      const RobotPose& p = c.read<RobotPose>();
      const Eigen::Vector3d truth = world.robotPose(0);
      const CalibrationRequest& q = c.read<CalibrationRequest>();
      const CalibrationStatus& st = c.read<CalibrationStatus>();
      std::fprintf(stderr, "  %5.1f s: truth (%.2f %.2f %.0f) est (%.2f %.2f %.0f)%s req %s view %d; last %d %s; samples %d/%d\n",
                   world.time() - t0, truth.x(), truth.y(), truth.z() / kDeg, p.pose.x, p.pose.y, p.pose.theta / kDeg,
                   p.valid ? "" : " invalid", calibrationActionName(q.action), q.viewId, st.last.viewId,
                   st.last.reason.c_str(), st.samples[0], st.samples[1]);
    }
    const SpeechRequest& speech = bb.read<SpeechRequest>();
    if (speech.id != lastSpeech) {
      lastSpeech = speech.id;
      std::fprintf(stderr, "  %.1f s: says '%s'\n", world.time() - t0, speech.text.c_str());
      if (speech.text == "Calibration finished") {
        r.finished = true;
        r.simSeconds = world.time() - t0;
        r.armUpAtSpeech = world.handPosition(0, false).z() > 0.5;
        break;
      }
    }
  }
  const CalibrationStatus& status = program.cognitionBoard().read<CalibrationStatus>();
  r.applied = status.applied;
  r.appliedId = status.appliedId;
  r.samples = status.samples;
  const CalibrationStatus& cs = program.cognitionBoard().read<CalibrationStatus>();
  r.calibrateState = "last view " + std::to_string(cs.last.viewId) + " " + cs.last.reason + ", solve " +
                     std::to_string(cs.solutionId) + " " + cs.reason;
  return r;
}

void expectCalibrated(const std::array<double, 6>& injectedDeg, int sideSign, std::uint64_t seed) {
  std::array<double, 6> rad{};
  for (int k = 0; k < 6; ++k) rad[k] = injectedDeg[k] * kDeg;
  const CameraCalibration injected = CameraCalibration::fromArray(rad);
  const Phase1 r = runPhase1(injected, sideSign, seed, 120);
  EXPECT_TRUE(r.finished) << r.calibrateState;
  EXPECT_FALSE(r.fell) << "tilted up to " << r.maxTiltDeg << " deg";
  EXPECT_GT(r.appliedId, 0) << "no calibration applied: " << r.calibrateState;
  const auto est = r.applied.toArray();
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(est[k] / kDeg, injectedDeg[k], 0.15) << "offset " << k;
  EXPECT_LT(r.maxStep, 0.02) << "the robot jumped: it must walk";
  EXPECT_GT(r.pathLength, 1.0) << "it must walk from the start to the goal box";
  EXPECT_TRUE(r.armUpAtSpeech);
  EXPECT_LE(r.simSeconds, 120);
  std::fprintf(stderr, "phase 1: %.1f s, samples %d/%d, path %.2f m\n", r.simSeconds, r.samples[0], r.samples[1],
               r.pathLength);
}

TEST(CalibrationPhase1, FromTheRightSideLine) { expectCalibrated({2.1, -2.6, -1.8, 2.9, 1.2, -2.3}, -1, 3); }

TEST(CalibrationPhase1, FromTheLeftSideLine) { expectCalibrated({-2.8, 1.7, 2.5, -1.1, -2.9, 2.2}, +1, 8); }

}  // namespace
}  // namespace nao
