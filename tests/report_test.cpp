// How the robot reports in the calibration challenge (../shared/reference/calibration-challenge.md):
// one arm raised (the simulated joints, judged by the hand's true position, with no fall), the
// Report option's order (arm up, then speech, hold, lower), and the NAO's voice (SpeechOutput:
// a text-to-speech command, off the motion thread, never fatal).
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <string>
#include <vector>

#include "controllers/RobotProgram.h"
#include "controllers/StandController.h"
#include "controllers/behavior/Report.h"
#include "representations/behavior/ArmMotionRequest.h"
#include "robot/nao/SpeechOutput.h"
#include "sim/SimBackend.h"
#include "sim/World.h"

namespace nao {
namespace {

using Arm = ArmMotionRequest::Arm;

// A robot standing at the origin, its program without a behaviour: the test writes the requests.
struct StandingRobot {
  sim::World world{sim::SceneSpec{}, 3};
  std::unique_ptr<sim::SimBackend> backend;
  std::unique_ptr<RobotProgram> program;
  double minTorsoZ = 1, maxTilt = 0;
  StandingRobot() {
    world.placeRobot(0, Eigen::Vector3d::Zero(), StandController::standPosture());
    backend = std::make_unique<sim::SimBackend>(world, 0);
    RobotProgramConfig config;
    config.withoutBehavior();
    program = std::make_unique<RobotProgram>(config);
  }
  void run(double seconds) {
    for (double t = 0; t < seconds - 1e-9; t += kCycleTime) {
      ASSERT_TRUE(program->cycle(*backend));
      const Eigen::Isometry3d torso = world.torsoPose(0);
      minTorsoZ = std::min(minTorsoZ, torso.translation().z());
      maxTilt = std::max(maxTilt, std::acos(std::clamp(torso.linear()(2, 2), -1.0, 1.0)));
    }
  }
  void raise(Arm arm) { program->blackboard().write<ArmMotionRequest>().raise = arm; }
  const MotionInfo& info() const { return program->blackboard().read<MotionInfo>(); }
  // The hand's height over the top camera's (the forehead): positive only for a raised hand.
  double handOverHead(bool left) const {
    return world.handPosition(0, left).z() - world.cameraPose(0, CameraId::Top).translation().z();
  }
  // Down: the hand hangs beside the hip, more than 15 cm below the forehead.
  bool handDown(bool left) const { return handOverHead(left) < -0.15; }
  void settle() {
    run(1.5);  // after the placement
    standingZ = world.torsoPose(0).translation().z();
    minTorsoZ = standingZ;
    maxTilt = 0;
  }
  double standingZ = 0;
};

TEST(ArmMotion, TheRaisedArmIsAboveTheHeadAndTheRobotStands) {
  StandingRobot r;
  r.settle();
  EXPECT_TRUE(r.handDown(false));
  EXPECT_FALSE(r.info().armRaised);
  r.raise(Arm::Right);
  r.run(1.0);
  EXPECT_TRUE(r.info().armRaised);
  EXPECT_GT(r.handOverHead(false), 0.0) << "the right hand is not above the head";
  std::printf("raised: the right wrist %.0f mm above the top camera, the left %.0f mm below it\n",
              r.handOverHead(false) * 1000, -r.handOverHead(true) * 1000);
  EXPECT_TRUE(r.handDown(true)) << "the left hand moved too";
  const Eigen::Vector3d before = r.world.robotPose(0);
  r.run(10.0);  // held: no fall, no sway worth the name, no step
  EXPECT_TRUE(r.info().armRaised);
  EXPECT_GT(r.minTorsoZ, r.standingZ - 0.02);
  EXPECT_LT(r.maxTilt, 10 * M_PI / 180);
  EXPECT_LT((r.world.robotPose(0).head<2>() - before.head<2>()).norm(), 0.01);
  r.raise(Arm::None);
  r.run(1.0);
  EXPECT_FALSE(r.info().armRaised);
  EXPECT_TRUE(r.handDown(false)) << "the right hand did not come down";
  // The other arm, then the first again without lowering in between: the left one goes down
  // before the right one rises.
  r.raise(Arm::Left);
  r.run(1.0);
  EXPECT_TRUE(r.info().armRaised);
  EXPECT_GT(r.handOverHead(true), 0.0);
  r.raise(Arm::Right);
  r.run(0.3);
  EXPECT_FALSE(r.info().armRaised);
  r.run(1.5);
  EXPECT_TRUE(r.info().armRaised);
  EXPECT_GT(r.handOverHead(false), 0.0);
  EXPECT_TRUE(r.handDown(true));
  EXPECT_GT(r.minTorsoZ, r.standingZ - 0.02);
  EXPECT_LT(r.maxTilt, 10 * M_PI / 180);
}

TEST(ArmMotion, WalkingLowersTheArm) {
  StandingRobot r;
  r.settle();
  r.raise(Arm::Right);
  r.run(1.0);
  ASSERT_TRUE(r.info().armRaised);
  MotionRequest walk;
  walk.motion = MotionType::Walk;
  walk.walkSpeed = Pose2(0.15, 0, 0);
  r.program->blackboard().write<MotionRequest>() = walk;
  r.run(2.0);
  EXPECT_FALSE(r.info().armRaised);
  EXPECT_TRUE(r.handDown(false));
  EXPECT_GT(r.world.robotPose(0).x(), 0.1) << "the robot did not walk";
  EXPECT_GT(r.minTorsoZ, r.standingZ - 0.02);
  r.program->blackboard().write<MotionRequest>() = MotionRequest{};  // stand: the arm rises again
  r.run(2.5);
  EXPECT_TRUE(r.info().armRaised);
  EXPECT_GT(r.handOverHead(false), 0.0);
}

// The option's order: the arm first, the words once it is up (or after the time-out), held,
// then lowered; a new start restarts it.
TEST(Report, ArmThenSpeechThenHoldThenLower) {
  RobotPose pose;
  BallModel ball;
  GameState game;
  FallState fall;
  MotionInfo motion;
  BehaviorCommand command;
  behavior::BehaviorInput in{0.0, pose, ball, game, fall, motion, command};
  behavior::Report::Params p;
  p.holdTime = 2.0;
  p.armTimeout = 3.0;
  behavior::Report report(p);
  ArmMotionRequest arm;
  SpeechRequest speech;
  EXPECT_FALSE(report.run(in, arm, speech));
  EXPECT_EQ(arm.raise, Arm::None);
  report.start("Finished walking", 0.0);
  auto at = [&](double t) {
    in.time = t;
    return report.run(in, arm, speech);
  };
  EXPECT_FALSE(at(0.1));
  EXPECT_EQ(arm.raise, Arm::Right);
  EXPECT_EQ(speech.id, 0) << "spoke before the arm was up";
  motion.armRaised = true;
  EXPECT_FALSE(at(0.7));
  EXPECT_EQ(speech.id, 1);
  EXPECT_EQ(speech.text, "Finished walking");
  EXPECT_FALSE(at(2.6));
  EXPECT_EQ(arm.raise, Arm::Right);
  EXPECT_TRUE(at(2.8));
  EXPECT_EQ(arm.raise, Arm::None);
  EXPECT_EQ(speech.id, 1) << "said twice";
  EXPECT_TRUE(at(3.0));
  // The arm never comes up (the robot is walking): it speaks after the time-out all the same.
  motion.armRaised = false;
  report.start("The ball is at: 1200 -300", 10.0);
  EXPECT_FALSE(at(12.9));
  EXPECT_EQ(speech.id, 1);
  EXPECT_FALSE(at(13.0));
  EXPECT_EQ(speech.id, 2);
  EXPECT_EQ(speech.text, "The ball is at: 1200 -300");
}

// ---- the NAO's voice ----------------------------------------------------------------------

struct Logged {
  std::mutex mutex;
  std::vector<std::string> lines;
  SpeechOutput::Log log() {
    return [this](const std::string& l) {
      std::lock_guard<std::mutex> lock(mutex);
      lines.push_back(l);
    };
  }
  std::string all() {
    std::lock_guard<std::mutex> lock(mutex);
    std::string s;
    for (const auto& l : lines) s += l + "\n";
    return s;
  }
};

std::string tempDir() {
  char dir[] = "/tmp/report_test.XXXXXX";
  EXPECT_NE(mkdtemp(dir), nullptr);
  return dir;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

template <class F>
bool waitFor(F done, double seconds = 20) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!done()) {
    if (std::chrono::steady_clock::now() > end) return false;
    usleep(5000);
  }
  return true;
}

TEST(SpeechOutput, EachUtteranceGoesToTheCommandInOrder) {
  const std::string dir = tempDir(), said = dir + "/said.txt", say = dir + "/say.sh";
  std::ofstream(say) << "#!/bin/sh\n[ \"$1\" = -t ] || exit 3\nprintf '%s|\\n' \"$2\" >> '" << said << "'\n";
  std::filesystem::permissions(say, std::filesystem::perms::owner_all);
  Logged logged;
  {
    SpeechOutput speech(say + " -t", logged.log());
    speech.say("Calibration finished");
    speech.say("The ball is at: -1500 2250");
    speech.say("it's \"quoted\"; $HOME `and` spaced  twice");
    ASSERT_TRUE(waitFor([&] { return speech.spoken() == 3; }));
    EXPECT_EQ(speech.failed(), 0);
  }
  // Verbatim, one argument each: no shell in between.
  EXPECT_EQ(readFile(said), "Calibration finished|\nThe ball is at: -1500 2250|\nit's \"quoted\"; $HOME `and` spaced  twice|\n");
  EXPECT_NE(logged.all().find("speech: Calibration finished\n"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(SpeechOutput, AMissingOrFailingCommandIsLoggedNotFatal) {
  Logged logged;
  {
    SpeechOutput speech("/nonexistent/flite -t", logged.log());
    speech.say("Finished walking");
    ASSERT_TRUE(waitFor([&] { return speech.failed() == 1; }));
    EXPECT_EQ(speech.spoken(), 0);
  }
  EXPECT_NE(logged.all().find("speech: Finished walking\n"), std::string::npos);
  EXPECT_NE(logged.all().find("the command '/nonexistent/flite' failed (cannot start"), std::string::npos)
      << logged.all();
  Logged failing;
  {
    SpeechOutput speech("false", failing.log());
    speech.say("x");
    ASSERT_TRUE(waitFor([&] { return speech.failed() == 1; }));
  }
  EXPECT_NE(failing.all().find("failed (exit status 1"), std::string::npos) << failing.all();
  Logged quiet;
  {
    SpeechOutput speech("", quiet.log());  // --speech-command none: the log only
    speech.say("Calibration finished");
    ASSERT_TRUE(waitFor([&] { return quiet.all().find("speech: Calibration finished") != std::string::npos; }));
    EXPECT_EQ(speech.failed(), 0);
  }
}

TEST(SpeechOutput, AHungCommandDoesNotHoldTheStop) {
  Logged logged;
  const auto start = std::chrono::steady_clock::now();
  {
    SpeechOutput speech("sleep", logged.log());
    speech.say("600");  // `sleep 600`: a text-to-speech that never returns
    speech.say("600");
    ASSERT_TRUE(waitFor([&] { return logged.all().find("speech: 600") != std::string::npos; }));
  }  // the destructor ends it
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 60.0);
}

}  // namespace
}  // namespace nao
