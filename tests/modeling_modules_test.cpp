// The modeling and behaviour modules of the robot program, each alone in the module harness
// with inputs made from a known truth: SelfLocalization, BallLocator, BehaviorControl (its
// GoToPose and LookActive options).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <set>

#include "controllers/StandController.h"
#include "controllers/behavior/LookActive.h"
#include "controllers/modules/BallLocator.h"
#include "controllers/modules/BehaviorControl.h"
#include "controllers/modules/CameraVision.h"
#include "controllers/modules/SelfLocalization.h"
#include "perception/CameraModel.h"
#include "perception/OwnBody.h"
#include "perception/calibration/CalibrationViews.h"
#include "representations/behavior/CalibrationRequest.h"
#include "representations/modeling/BallTracks.h"
#include "representations/modeling/FieldBalls.h"
#include "representations/perception/CalibrationStatus.h"
#include "robot/Paths.h"
#include "tests/support/ModuleHarness.h"

namespace nao {
namespace {

using testing::ModuleHarness;

const FieldModel& field() {
  static const FieldModel f = FieldModel::from(FieldDimensions::load(dataPath("config/field_dimensions.json")));
  return f;
}

ModuleContext fieldContext() {
  ModuleContext c;
  c.params["FieldDimensions"] = field().dims;
  return c;
}

// The field lines a robot at `pose` would see ahead (0.3-3.5 m, +-60 deg), robot frame, with
// noise: the longest visible run of each line, sampled every 5 cm.
std::vector<LinesPercept::Line> visibleLines(const Pose2& pose, std::mt19937& rng, double noise = 0.01) {
  std::normal_distribution<double> n(0, noise);
  std::vector<LinesPercept::Line> out;
  for (const FieldLine& fl : field().lines) {
    const double length = (fl.to - fl.from).norm();
    const int steps = std::max(2, static_cast<int>(length / 0.05));
    int bestStart = -1, bestEnd = -1, start = -1;
    for (int k = 0; k <= steps + 1; ++k) {
      bool visible = false;
      if (k <= steps) {
        const Eigen::Vector2d rel = pose.inverse() * (fl.from + (fl.to - fl.from) * (double(k) / steps));
        visible = rel.norm() > 0.3 && rel.norm() < 3.5 && std::abs(std::atan2(rel.y(), rel.x())) < 1.05;
      }
      if (visible && start < 0) start = k;
      if (!visible && start >= 0) {
        if (k - 1 - start > bestEnd - bestStart) bestStart = start, bestEnd = k - 1;
        start = -1;
      }
    }
    if (bestStart < 0 || (bestEnd - bestStart) * length / steps < 0.4) continue;
    LinesPercept::Line l;
    l.imageFrom = l.imageTo = Eigen::Vector2d::Zero();
    l.from = pose.inverse() * (fl.from + (fl.to - fl.from) * (double(bestStart) / steps)) + Eigen::Vector2d(n(rng), n(rng));
    l.to = pose.inverse() * (fl.from + (fl.to - fl.from) * (double(bestEnd) / steps)) + Eigen::Vector2d(n(rng), n(rng));
    out.push_back(l);
  }
  return out;
}

// A motion-side history with the odometry reading `odometry` from time t - 0.1 to t.
FrameHistory historyAt(double t, const Pose2& odometry) {
  FrameHistory h;
  for (int i = 0; i <= 8; ++i) {
    FrameHistory::Entry e;
    e.time = t - 0.1 + i * 0.0125;
    e.odometry = odometry;
    h.entries.push_back(e);
  }
  return h;
}

CameraPercepts perceptsAt(double t, CameraId camera = CameraId::Top) {
  CameraPercepts p;
  p.camera = camera;
  p.timestamp = t;
  p.processed = true;
  return p;
}

// The robot walks a square loop in its own half (starting from the side line, where the game
// situation says it enters), odometry 5 % long; the module sees the lines ahead every image.
TEST(SelfLocalizationModule, FollowsARobotFromTheSideLineWithItsOdometryAndLines) {
  ModuleHarness h("SelfLocalization", fieldContext());
  std::mt19937 rng(5);
  Pose2 truth(-2.0, -3.0, M_PI / 2), odometry;
  h.fix(GameState{}).fix(ChallengeMode{});
  int images = 0, valid = 0;
  double worst = 0;
  const Pose2 step(0.006, 0, 0.002);  // per image: 0.18 m/s, 3.4 deg/s
  for (int i = 0; i < 900; ++i) {
    const double t = i / 30.0;
    truth = truth * step;
    odometry = odometry * Pose2(step.x * 1.05, step.y, step.theta);
    CameraPercepts p = perceptsAt(t);
    p.lines = visibleLines(truth, rng);
    h.fix(p).fix(historyAt(t, odometry)).run();
    const RobotPose& pose = h.get<RobotPose>();
    ASSERT_TRUE(std::isfinite(pose.pose.x) && std::isfinite(pose.pose.theta));
    EXPECT_EQ(pose.time, t);
    ++images;
    if (i < 60 || !pose.valid) continue;
    ++valid;
    worst = std::max(worst, (pose.pose.translation() - truth.translation()).norm());
  }
  EXPECT_GT(valid, images * 8 / 10);
  EXPECT_LT(worst, 0.15) << "the estimate left the truth";
}

TEST(SelfLocalizationModule, BadInputsAreSkippedAndTheFilterStaysFinite) {
  ModuleHarness h("SelfLocalization", fieldContext());
  std::mt19937 rng(7);
  const Pose2 truth(-2.0, -3.0, M_PI / 2);
  h.fix(GameState{}).fix(ChallengeMode{});
  auto& module = dynamic_cast<const modules::SelfLocalization&>(h.module());
  for (int i = 0; i < 120; ++i) {
    const double t = i / 30.0;
    CameraPercepts p = perceptsAt(t);
    p.lines = visibleLines(truth, rng);
    Pose2 odometry;
    if (i == 50) odometry = Pose2(std::nan(""), 0, 0);           // a NaN odometry step
    if (i == 60) odometry = Pose2(0, 0, std::numeric_limits<double>::infinity());
    if (i == 70) p.timestamp = std::nan("");                      // an image without a time
    if (i == 80) p.timestamp = 0.5;                               // older than the last
    if (i == 90) p.lines[0].from = Eigen::Vector2d(std::nan(""), 1);  // a NaN percept
    if (i == 95) h.fix(FrameHistory{});                           // no history (no motion yet)
    else h.fix(historyAt(p.timestamp, odometry));
    h.fix(p).run();
    const RobotPose& pose = h.get<RobotPose>();
    ASSERT_TRUE(pose.covariance.allFinite() && std::isfinite(pose.pose.x) && std::isfinite(pose.pose.y) &&
                std::isfinite(pose.pose.theta))
        << "image " << i;
  }
  EXPECT_EQ(module.skippedImages(), 2);  // the NaN time and the missing history
  EXPECT_EQ(module.skippedOdometry(), 2);
  EXPECT_GE(module.locator().stats().skippedPercepts, 1);
  const RobotPose& pose = h.get<RobotPose>();
  EXPECT_TRUE(pose.valid);
  EXPECT_LT((pose.pose.translation() - truth.translation()).norm(), 0.1);
}

TEST(SelfLocalizationModule, APenaltyEndsWithTheRobotAtThePenaltyMarkSideLines) {
  ModuleHarness h("SelfLocalization", fieldContext());
  GameState game;
  h.fix(ChallengeMode{});
  h.fix(game).fix(perceptsAt(0)).fix(historyAt(0, Pose2())).run();
  game.penalty = gc::Penalty::PlayerPushing;
  h.fix(game).fix(perceptsAt(1)).run();
  game.penalty = gc::Penalty::None;
  h.fix(game).fix(perceptsAt(2)).fix(historyAt(2, Pose2())).run();
  const auto& hyps = dynamic_cast<const modules::SelfLocalization&>(h.module()).locator().hypotheses();
  ASSERT_FALSE(hyps.empty());
  const double markX = -field().halfLength() + field().dims.penaltyCrossDistance;
  for (const auto& hyp : hyps) {
    EXPECT_NEAR(hyp.mean.x(), markX, 0.01);
    EXPECT_NEAR(std::abs(hyp.mean.y()), field().halfWidth(), 0.01);
  }
}

// A challenge start (the referee's buttons; the robot was placed at the start) forgets where
// the robot was and puts it on the side lines in line with the own penalty mark, as the rules do.
TEST(SelfLocalizationModule, AChallengeStartPutsTheRobotOnTheSideLinesAtThePenaltyMark) {
  ModuleHarness h("SelfLocalization", fieldContext());
  ChallengeMode mode;
  h.fix(GameState{}).fix(mode);
  // Localized somewhere else first: the centre of the field, from a sideline entry.
  for (int i = 0; i < 3; ++i) h.fix(perceptsAt(i)).fix(historyAt(i, Pose2())).run();
  const double markX = -field().halfLength() + field().dims.penaltyCrossDistance;
  const auto& module = dynamic_cast<const modules::SelfLocalization&>(h.module());
  bool elsewhere = false;
  for (const auto& hyp : module.locator().hypotheses()) elsewhere |= std::abs(hyp.mean.x() - markX) > 0.5;
  EXPECT_TRUE(elsewhere) << "the sideline entry's hypotheses should not all be at the penalty mark";
  mode.mode = ChallengeMode::Mode::Calibration;
  mode.modeId = 1;
  h.fix(mode).fix(perceptsAt(3)).fix(historyAt(3, Pose2())).run();
  const auto& hyps = module.locator().hypotheses();
  ASSERT_EQ(hyps.size(), 2u);
  for (const auto& hyp : hyps) {
    EXPECT_NEAR(hyp.mean.x(), markX, 0.01);
    EXPECT_NEAR(std::abs(hyp.mean.y()), field().halfWidth(), 0.01);
    EXPECT_NEAR(hyp.mean.z(), hyp.mean.y() > 0 ? -M_PI / 2 : M_PI / 2, 0.01);  // facing into the field
  }
}

// The bottom camera looking down 1 m ahead of a standing robot.
CameraMatrix bottomCamera() {
  CameraMatrix m;
  m.intrinsics = CameraIntrinsics::nominal(CameraId::Bottom);
  const double pitch = std::atan2(0.45, 1.0);
  m.pose.linear() = Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()).toRotationMatrix();
  m.pose.translation() = Eigen::Vector3d(0.05, 0, 0.45);
  return m;
}

TEST(BallLocatorModule, ModelsTheBallThroughOdometryAndCallsItLostOnlyWhenItShouldBeSeen) {
  ModuleHarness h("BallLocator");
  RobotPose pose;
  pose.valid = true;
  pose.pose = Pose2(1, 0, 0);
  h.fix(pose);
  const Eigen::Vector2d ball(1.0, 0.1);
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0, 0.01);
  for (int i = 0; i < 30; ++i) {
    CameraPercepts p = perceptsAt(i / 30.0, CameraId::Bottom);
    p.cameraMatrix = bottomCamera();
    p.ball.seen = true;
    p.ball.position = ball + Eigen::Vector2d(n(rng), n(rng));
    p.ball.covariance = Eigen::Matrix2d::Identity() * 1e-4;
    h.fix(p).fix(historyAt(p.timestamp, Pose2())).run();
  }
  BallModel m = h.get<BallModel>();
  ASSERT_TRUE(m.valid);
  EXPECT_LT((m.position - ball).norm(), 0.02);
  EXPECT_TRUE(m.fieldValid);
  EXPECT_LT((m.fieldPosition - Eigen::Vector2d(2.0, 0.1)).norm(), 0.02);
  // The robot walks 0.3 m forward without seeing it (the camera looks elsewhere: not expected).
  CameraMatrix away = bottomCamera();
  away.pose.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix() * away.pose.linear();
  for (int i = 30; i < 60; ++i) {
    CameraPercepts p = perceptsAt(i / 30.0, CameraId::Bottom);
    p.cameraMatrix = away;
    h.fix(p).fix(historyAt(p.timestamp, Pose2(0.01 * (i - 29), 0, 0))).run();
  }
  m = h.get<BallModel>();
  EXPECT_FALSE(m.lost) << "out of view is no evidence";
  EXPECT_LT((m.position - (ball - Eigen::Vector2d(0.3, 0))).norm(), 0.03);
  // Now it should be in the bottom camera's image and is not there: lost after the filter's count.
  const int lostAfter = modules::BallLocator::Params{}.filter.lostAfterFrames;
  int frames = 0;
  for (int i = 60; i < 80 && !h.get<BallModel>().lost; ++i, ++frames) {
    CameraPercepts p = perceptsAt(i / 30.0, CameraId::Bottom);
    p.cameraMatrix = bottomCamera();
    ASSERT_TRUE(modules::BallLocator::expectedInView(h.get<BallModel>().position, p, modules::BallLocator::Params{}));
    h.fix(p).fix(historyAt(p.timestamp, Pose2(0.3, 0, 0))).run();
  }
  EXPECT_EQ(frames, lostAfter);
  // A NaN percept is skipped.
  CameraPercepts p = perceptsAt(3, CameraId::Bottom);
  p.ball.seen = true;
  p.ball.position = Eigen::Vector2d(std::nan(""), 0);
  h.fix(p).fix(historyAt(3, Pose2(0.3, 0, 0))).run();
  EXPECT_TRUE(h.get<BallModel>().position.allFinite());
  EXPECT_EQ(dynamic_cast<const modules::BallLocator&>(h.module()).filter().stats().skippedObservations, 1);
}

struct BehaviorFixture {
  ModuleHarness h{"BehaviorControl", fieldContext()};
  RobotPose pose;
  BehaviorFixture() {
    pose.valid = true;
    pose.covariance = Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal();
    h.fix(BallModel{}).fix(GameState{}).fix(FallState{}).fix(MotionInfo{}).fix(historyAt(1, Pose2())).fix(ChallengeMode{})
        .fix(CameraCalibration{}).fix(CalibrationStatus{}).fix(CameraPercepts{}).fix(FieldBalls{}).fix(BallTracks{});
  }
  void run(const RobotPose& p, const BehaviorCommand& c) { h.fix(p).fix(c).run(); }
};

// In the calibration mode: from the start, walk to the own goal box's side on the start's side
// line; there, turn and aim the head per view and ask the calibrator for each view's sample,
// one view after the other as the calibrator answers; with all views in, ask for a solve.
TEST(BehaviorControlModule, CalibratesViewByViewFromTheStart) {
  BehaviorFixture f;
  ChallengeMode mode;
  mode.mode = ChallengeMode::Mode::Calibration;
  mode.modeId = 1;
  f.h.fix(mode);
  const FieldDimensions& dims = field().dims;
  double t = 1;
  auto step = [&](const RobotPose& p, const MotionInfo& info, const CalibrationStatus& status) {
    t += 1.0 / 30;
    f.h.fix(historyAt(t, p.odometry)).fix(info).fix(status);
    f.run(p, BehaviorCommand{});
  };
  RobotPose pose = f.pose;
  pose.pose = Pose2(-3.2, -3.0, M_PI / 2);
  pose.odometry = pose.pose;  // the odometry frame is the field frame here
  CalibrationStatus status;
  MotionInfo walking;
  // No goal box side in view (no percepts here): the robot looks ahead, standing, until the
  // side timeout; then the localization decides the start side.
  for (int i = 0; i < 45; ++i) step(pose, walking, status);  // 1.5 s
  EXPECT_EQ(f.h.get<MotionRequest>().motion, MotionType::Stand);
  EXPECT_EQ(f.h.get<HeadMotionRequest>().yaw, 0.0);
  for (int i = 0; i < 100; ++i) step(pose, walking, status);  // 4.8 s
  const MotionRequest& walk = f.h.get<MotionRequest>();
  ASSERT_EQ(walk.motion, MotionType::WalkTo);
  const Eigen::Vector3d target = calibration::calibrationPosition(calibration::ownGoalBoxSide(dims, -1));
  // The target in the odometry frame is the field target (odometry = field here).
  EXPECT_NEAR(walk.walkTarget.x, target.x(), 1e-6);
  EXPECT_NEAR(walk.walkTarget.y, target.y(), 1e-6);
  EXPECT_EQ(f.h.get<CalibrationRequest>().action, CalibrationRequest::Action::Idle);
  // Arrived: the views begin.
  pose.pose = Pose2(target.x(), target.y(), target.z());
  pose.odometry = pose.pose;
  MotionInfo reached;
  reached.walkToReached = true;
  // (It looks for the box's short line to align with first; with none in view it goes on from here.)
  for (int i = 0; i < 90 && f.h.get<CalibrationRequest>().action != CalibrationRequest::Action::Collect; ++i)
    step(pose, reached, status);
  const std::vector<calibration::CalibrationView> views = calibration::planViews(
      calibration::ownGoalBoxSide(dims, -1), target.head<2>(), StandController::standPosture());
  std::vector<int> asked;
  for (std::size_t v = 0; v < views.size(); ++v) {
    const CalibrationRequest& q = f.h.get<CalibrationRequest>();
    ASSERT_EQ(q.action, CalibrationRequest::Action::Collect) << "view " << v;
    EXPECT_EQ(q.camera, views[v].camera);
    EXPECT_NEAR(f.h.get<HeadMotionRequest>().yaw, views[v].headYaw, 1e-9);
    EXPECT_NEAR(f.h.get<HeadMotionRequest>().pitch, views[v].headPitch, 1e-9);
    EXPECT_NEAR(Pose2::wrap(f.h.get<MotionRequest>().walkTarget.theta - views[v].robotPose.z()), 0, 1e-6);
    asked.push_back(q.viewId);
    // The calibrator answers: a sample.
    status.last.viewId = q.viewId;
    status.last.accepted = true;
    status.last.imageTime = t;
    ++status.samples[static_cast<int>(q.camera)];
    for (int i = 0; i < 30; ++i) {
      step(pose, reached, status);
      if (f.h.get<CalibrationRequest>().action != CalibrationRequest::Action::Idle &&
          f.h.get<CalibrationRequest>().viewId != q.viewId)
        break;
    }
  }
  EXPECT_EQ(std::set<int>(asked.begin(), asked.end()).size(), views.size()) << "one view id per view";
  EXPECT_EQ(f.h.get<CalibrationRequest>().action, CalibrationRequest::Action::Solve);
  EXPECT_EQ(f.h.get<MotionRequest>().motion, MotionType::Stand);
}

// In the evaluation mode: the own half's ball first. Walk to 0.9 m short of it facing it, stand
// and look at it until 30 new observations are in, report its near median in millimetres with an
// arm up; after the referee's tap, walk to the own goal's centre facing the field.
TEST(BehaviorControlModule, ReportsTheOwnBallThenWalksToTheOwnGoalAfterTheTap) {
  BehaviorFixture f;
  ChallengeMode mode;
  mode.mode = ChallengeMode::Mode::Evaluation;
  mode.modeId = 1;
  double t = 1;
  RobotPose pose = f.pose;
  pose.pose = Pose2(-3.2, -3.0, M_PI / 2);
  pose.odometry = pose.pose;
  FieldBalls balls;
  balls.own.seen = true;
  balls.own.support = 20;
  balls.own.position = Eigen::Vector2d(-2, 0);
  balls.own.lastSeen = t;
  MotionInfo info;
  auto step = [&] {
    t += 1.0 / 30;
    pose.time = t;
    f.h.fix(historyAt(t, pose.odometry)).fix(info).fix(balls).fix(mode);
    f.run(pose, BehaviorCommand{});
  };
  for (int i = 0; i < 60; ++i) step();  // settled and localized
  const MotionRequest& walk = f.h.get<MotionRequest>();
  ASSERT_EQ(walk.motion, MotionType::WalkTo);
  const Eigen::Vector2d toBall = (Eigen::Vector2d(-2, 0) - Eigen::Vector2d(-3.2, -3.0)).normalized();
  const Eigen::Vector2d observeAt = Eigen::Vector2d(-2, 0) - 0.9 * toBall;
  EXPECT_NEAR(walk.walkTarget.x, observeAt.x(), 1e-6);
  EXPECT_NEAR(walk.walkTarget.y, observeAt.y(), 1e-6);
  EXPECT_NEAR(walk.walkTarget.theta, std::atan2(toBall.y(), toBall.x()), 1e-6);
  // Arrived: it stands and looks at the ball; each image adds a near observation.
  pose.pose = Pose2(observeAt.x(), observeAt.y(), std::atan2(toBall.y(), toBall.x()));
  pose.odometry = pose.pose;
  info.walkToReached = true;
  balls.own.closePosition = Eigen::Vector2d(-2.013, 0.004);
  balls.own.close = 40;
  int images = 0;
  for (; images < 100 && f.h.get<ArmMotionRequest>().raise == ArmMotionRequest::Arm::None; ++images) {
    balls.own.lastSeen = t;
    step();
    if (images > 2) {
      EXPECT_EQ(f.h.get<MotionRequest>().motion, MotionType::Stand);
      EXPECT_EQ(f.h.get<HeadMotionRequest>().mode, HeadMotionRequest::Mode::LookAtFieldPoint);
    }
  }
  EXPECT_GE(images, 30) << "reported before 30 observations";
  info.armRaised = true;
  for (int i = 0; i < 5; ++i) step();
  EXPECT_EQ(f.h.get<SpeechRequest>().text, "The ball is at: -2013 4");
  // The report held, the arm lowered: it waits for the tap, then walks to the own goal.
  info.armRaised = false;
  for (int i = 0; i < 90; ++i) step();
  EXPECT_EQ(f.h.get<MotionRequest>().motion, MotionType::Stand);
  const int id = f.h.get<MotionRequest>().walkTargetId;
  mode.headTaps = 1;
  info.walkToReached = false;
  step();
  step();
  ASSERT_EQ(f.h.get<MotionRequest>().motion, MotionType::WalkTo);
  EXPECT_NE(f.h.get<MotionRequest>().walkTargetId, id) << "a new target needs a new id";
  EXPECT_NEAR(f.h.get<MotionRequest>().walkTarget.x, -4.5, 1e-6);
  EXPECT_NEAR(f.h.get<MotionRequest>().walkTarget.y, 0, 1e-6);
  EXPECT_NEAR(f.h.get<MotionRequest>().walkTarget.theta, 0, 1e-6);
}

TEST(BehaviorControlModule, SaysWhenTheRefereeStartsAChallengeMode) {
  BehaviorFixture f;
  RobotPose pose;
  f.run(pose, BehaviorCommand{});
  EXPECT_EQ(f.h.get<SpeechRequest>().id, 0);
  ChallengeMode mode;
  mode.mode = ChallengeMode::Mode::Calibration;
  mode.modeId = 1;
  f.h.fix(mode);
  f.run(pose, BehaviorCommand{});
  EXPECT_EQ(f.h.get<SpeechRequest>().text, "Calibration mode");
  EXPECT_EQ(f.h.get<SpeechRequest>().id, 1);
  f.run(pose, BehaviorCommand{});
  EXPECT_EQ(f.h.get<SpeechRequest>().id, 1) << "said twice";
  mode.mode = ChallengeMode::Mode::Evaluation;
  mode.modeId = 2;
  f.h.fix(mode);
  f.run(pose, BehaviorCommand{});
  EXPECT_EQ(f.h.get<SpeechRequest>().text, "Evaluation mode");
  EXPECT_EQ(f.h.get<SpeechRequest>().id, 2);
  EXPECT_EQ(f.h.get<ArmMotionRequest>().raise, ArmMotionRequest::Arm::None);  // no report: no arm
}

TEST(BehaviorControlModule, WalksToTheCommandedPoseInTheOdometryFrameAndKeepsItsTargetThroughJitter) {
  BehaviorFixture f;
  BehaviorCommand command;
  command.goTo = Pose2(2, 1, M_PI / 2);
  // Localized at (0, 0, 0) while the odometry reads (5, 5, pi/2): the target in the odometry
  // frame is odometry * (pose^-1 * target).
  f.pose.pose = Pose2(0, 0, 0);
  f.pose.odometry = Pose2(5, 5, M_PI / 2);
  f.run(f.pose, command);
  const MotionRequest r = f.h.get<MotionRequest>();
  EXPECT_EQ(r.motion, MotionType::WalkTo);
  EXPECT_TRUE(r.walkTargetInOdometry);
  const Pose2 expected = f.pose.odometry * Pose2(2, 1, M_PI / 2);
  EXPECT_NEAR(r.walkTarget.x, expected.x, 1e-9);
  EXPECT_NEAR(r.walkTarget.y, expected.y, 1e-9);
  EXPECT_NEAR(r.walkTarget.theta, expected.theta, 1e-9);
  // 2 cm of estimate jitter far from the target: the same target and id.
  f.pose.pose = Pose2(0.02, -0.02, 0.01);
  f.run(f.pose, command);
  EXPECT_EQ(f.h.get<MotionRequest>().walkTargetId, r.walkTargetId);
  // The estimate corrected by 30 cm: a new target.
  f.pose.pose = Pose2(0.3, 0, 0);
  f.run(f.pose, command);
  EXPECT_NE(f.h.get<MotionRequest>().walkTargetId, r.walkTargetId);
  // Without a valid pose: stand, and the head sweeps to find the field.
  f.pose.valid = false;
  f.run(f.pose, command);
  EXPECT_EQ(f.h.get<MotionRequest>().motion, MotionType::Stand);
  EXPECT_EQ(f.h.get<HeadMotionRequest>().mode, HeadMotionRequest::Mode::Sweep);
  // No command: stand.
  f.pose.valid = true;
  f.run(f.pose, BehaviorCommand{});
  EXPECT_EQ(f.h.get<MotionRequest>().motion, MotionType::Stand);
}

TEST(BehaviorControlModule, TheHeadTracksAKnownBallWithTheCameraThatSeesItBest) {
  BehaviorFixture f;
  BallModel ball;
  ball.valid = true;
  ball.seenTime = 0.9;
  ball.position = Eigen::Vector2d(0.5, 0.2);
  f.h.fix(ball);
  f.run(f.pose, BehaviorCommand{});
  const HeadMotionRequest& head = f.h.get<HeadMotionRequest>();
  EXPECT_EQ(head.mode, HeadMotionRequest::Mode::LookAtRobotPoint);
  EXPECT_EQ(head.camera, CameraId::Bottom);
  EXPECT_NEAR(head.point.x(), 0.5, 1e-9);
  ball.position = Eigen::Vector2d(3, 0);
  f.h.fix(ball);
  f.run(f.pose, BehaviorCommand{});
  EXPECT_EQ(f.h.get<HeadMotionRequest>().camera, CameraId::Top);
  EXPECT_GT(f.h.get<HeadMotionRequest>().maxSpeed, 0);  // limited for the images' sake
}

TEST(CameraVisionModule, AnImpossibleCameraMatrixIsSkippedNotSeenThrough) {
  ModuleHarness h("CameraVision", fieldContext());
  CurrentImage current;
  CameraImage& image = current.image;
  image.camera = CameraId::Bottom;
  image.timestamp = 1.0;
  image.width = 320;
  image.height = 240;
  image.yuyv.assign(static_cast<std::size_t>(image.width) * image.height * 2, 128);
  ImageCameraMatrix m;
  m.camera = CameraId::Bottom;
  m.timestamp = 1.0;
  m.valid = true;
  m.matrix = bottomCamera();
  m.matrix.intrinsics = CameraIntrinsics::fromFovY(image.width, image.height);
  h.fix(current).fix(m).fix(OwnBody{}).run();
  EXPECT_TRUE(h.get<CameraPercepts>().processed);
  // Under the ground, NaN, not a rotation: each refused, the percept set marked unprocessed.
  for (int k = 0; k < 3; ++k) {
    ImageCameraMatrix bad = m;
    if (k == 0) bad.matrix.pose.translation().z() = -0.3;
    if (k == 1) bad.matrix.pose.linear()(0, 0) = std::nan("");
    if (k == 2) bad.matrix.pose.linear() *= 2.0;
    h.fix(bad).run();
    const CameraPercepts& p = h.get<CameraPercepts>();
    EXPECT_FALSE(p.processed) << k;
    EXPECT_TRUE(p.lines.empty() && !p.ball.seen) << k;
    EXPECT_EQ(p.timestamp, 1.0);
  }
}

TEST(LookActive, LooksWhereTheFeaturesShrinkTheUncertaintyMost) {
  behavior::LookActive look(field());
  // Standing on the halfway line's end facing the field, uncertain across the field (y):
  // the halfway line ahead tells nothing about y; the side line's points say little about x...
  const Pose2 pose(0, -2.5, M_PI / 2);
  const Eigen::Matrix3d uncertainInY = Eigen::Vector3d(0.0001, 0.09, 0.0001).asDiagonal();
  const int best = look.choose(pose, uncertainInY, 0);
  ASSERT_GE(best, 0);
  const auto& f = look.features()[best];
  // ... so it picks a feature that constrains y: a point feature or a line running along x.
  if (f.onLine) {
    EXPECT_GT(std::abs(f.normal.y()), 0.9);
  }
  // A feature behind the robot or too far is worth nothing.
  behavior::LookActive::Feature behind{Eigen::Vector2d(0, -4.0)};
  EXPECT_EQ(look.informationGain(behind, pose, uncertainInY), 0);
  behavior::LookActive::Feature far{Eigen::Vector2d(0, 3.0)};
  EXPECT_EQ(look.informationGain(far, pose, uncertainInY), 0);
  // A nearer point feature is worth more than a farther one.
  behavior::LookActive::Feature near{Eigen::Vector2d(0, -1.5)}, mid{Eigen::Vector2d(0, 1.0)};
  EXPECT_GT(look.informationGain(near, pose, uncertainInY), look.informationGain(mid, pose, uncertainInY));
  // Certain already: nothing to gain.
  EXPECT_LT(look.informationGain(near, pose, Eigen::Matrix3d::Identity() * 1e-10), 1e-6);
}

}  // namespace
}  // namespace nao
