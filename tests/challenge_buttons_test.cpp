// The calibration challenge's buttons (../shared/reference/calibration-challenge.md) through the
// robot's own touch sensors: the simulator presses them as a referee would (World::setTouch, what
// a NAO reports in LoLA's Touch array), the robot program's ButtonStateProvider and
// ChallengeModeProvider turn them into the mode, and the robot stands still meanwhile.
#include <gtest/gtest.h>

#include <initializer_list>

#include "controllers/RobotProgram.h"
#include "controllers/StandController.h"
#include "controllers/modules/ChallengeModeProvider.h"
#include "perception/FieldDimensions.h"
#include "representations/behavior/SpeechRequest.h"
#include "representations/infrastructure/ChallengeMode.h"
#include "robot/Paths.h"
#include "scenarios/Calibrate.h"
#include "sim/SimBackend.h"
#include "sim/World.h"
#include "tests/support/ModuleHarness.h"

namespace nao {
namespace {

using testing::ModuleHarness;

TEST(ChallengeModeProvider, StartsModesAndCountsTaps) {
  ModuleHarness h = ModuleHarness::make<modules::ChallengeModeProvider>();
  SensorFrame f;
  auto step = [&](std::initializer_list<ButtonEvent> events) {
    f.time += 0.012;
    ButtonState b;
    b.events = events;
    h.fix(b).fix(f).run();
    return h.get<ChallengeMode>();
  };
  EXPECT_EQ(step({}).mode, ChallengeMode::Mode::None);
  EXPECT_EQ(step({ButtonEvent::HeadTap}).headTaps, 0);  // no mode: a tap means nothing
  EXPECT_EQ(step({ButtonEvent::ChestPress}).mode, ChallengeMode::Mode::None);
  ChallengeMode m = step({ButtonEvent::StartCalibration});
  EXPECT_EQ(m.mode, ChallengeMode::Mode::Calibration);
  EXPECT_EQ(m.modeId, 1);
  EXPECT_NEAR(m.since, f.time, 1e-12);
  step({ButtonEvent::HeadTap});
  EXPECT_EQ(step({ButtonEvent::HeadTap}).headTaps, 2);
  m = step({ButtonEvent::StartCalibrationEvaluation});
  EXPECT_EQ(m.mode, ChallengeMode::Mode::Evaluation);
  EXPECT_EQ(m.modeId, 2);
  EXPECT_EQ(m.headTaps, 0);
  EXPECT_EQ(step({ButtonEvent::StartCalibrationEvaluation}).modeId, 3);  // a restart is a new start
}

// The referee's hands on the simulated robot: chest + head front held 0.9 s does nothing, 1.2 s
// starts calibration; a tap of the middle head button counts; chest + head rear starts the
// evaluation. The robot stands where it was placed all the while (truth).
TEST(ChallengeButtons, TheRefereesButtonsOnTheSimulatedRobot) {
  const FieldDimensions field = FieldDimensions::load(dataPath("config/field_dimensions.json"));
  sim::SceneSpec spec;
  spec.field = field;
  const Eigen::Vector3d start(-3.2, -3.0, M_PI / 2);
  spec.robots = {start};
  sim::World world(spec, 5);
  world.placeRobot(0, start, StandController::standPosture());
  sim::SimBackend backend(world, 0, true);
  // The camera shield on: dark frames (cognition, and so the behaviour, runs per frame).
  backend.setImageSource(
      [&](CameraId cam, double time, const ExposureWeights&) { return sim::shieldFrame(world, cam, time); });
  RobotProgramConfig config;
  config.field = field;
  RobotProgram program(config);
  const Blackboard& bb = program.blackboard();
  auto hold = [&](std::initializer_list<Touch> touched, double seconds) {
    for (Touch t : touched) world.setTouch(0, t, 1.0);
    for (double t = 0; t < seconds - 1e-9; t += 0.012) ASSERT_TRUE(program.cycle(backend));
    for (Touch t : touched) world.setTouch(0, t, 0.0);
  };
  hold({}, 1.0);  // the stand settles after the placement
  const Eigen::Vector3d settled = world.robotPose(0);
  hold({ChestButton, HeadFront}, 0.9);
  hold({}, 0.5);
  EXPECT_EQ(bb.read<ChallengeMode>().mode, ChallengeMode::Mode::None);
  EXPECT_EQ(bb.read<ChallengeMode>().modeId, 0);
  EXPECT_EQ(bb.read<SpeechRequest>().id, 0) << "said '" << bb.read<SpeechRequest>().text << "' before any mode";
  hold({ChestButton, HeadFront}, 1.2);
  hold({}, 0.5);
  EXPECT_EQ(bb.read<ChallengeMode>().mode, ChallengeMode::Mode::Calibration);
  // The behaviour acknowledges the mode aloud (the request crosses back to motion, where the
  // backend's voice takes it).
  EXPECT_EQ(bb.read<SpeechRequest>().text, "Calibration mode");
  EXPECT_EQ(bb.read<SpeechRequest>().id, 1);
  EXPECT_EQ(bb.read<ChallengeMode>().modeId, 1);
  EXPECT_NEAR(bb.read<ChallengeMode>().since, 1.0 + 0.9 + 0.5 + 1.0, 0.05);  // when the hold reached 1 s
  hold({HeadMiddle}, 0.2);
  hold({}, 0.3);
  EXPECT_EQ(bb.read<ChallengeMode>().headTaps, 1);
  hold({ChestButton, HeadRear}, 1.2);
  hold({}, 0.5);
  EXPECT_EQ(bb.read<ChallengeMode>().mode, ChallengeMode::Mode::Evaluation);
  EXPECT_EQ(bb.read<ChallengeMode>().modeId, 2);
  EXPECT_EQ(bb.read<SpeechRequest>().text, "Evaluation mode");
  EXPECT_EQ(bb.read<SpeechRequest>().id, 2);
  EXPECT_EQ(bb.read<ChallengeMode>().headTaps, 0);
  const Eigen::Vector3d now = world.robotPose(0);
  EXPECT_LT((now.head<2>() - settled.head<2>()).norm(), 0.01);
  EXPECT_LT(std::abs(now.z() - settled.z()), 0.02);
}

}  // namespace
}  // namespace nao
