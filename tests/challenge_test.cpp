// The calibration challenge's phase 2 parts, each against an independent truth: the per-half
// ball estimate (FieldBallLocator) with a false ball and far observations among the near ones;
// the detour round a known ball (ChallengeTasks) and the report's sentence; the referee's
// ball draw and its checks; and the termination rules judged from the simulator's truth
// (ChallengeReferee): a ball rolled into the feet, a robot beyond the side line, falls, a
// robot that does not get up.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "controllers/StandController.h"
#include "controllers/behavior/CalibrateCameras.h"
#include "controllers/behavior/ChallengeTasks.h"
#include "controllers/modules/FieldBallLocator.h"
#include "perception/calibration/CalibrationViews.h"
#include "robot/Error.h"
#include "robot/Paths.h"
#include "scenarios/CalibrationChallenge.h"
#include "scenarios/ChallengeReferee.h"
#include "scenarios/Venue.h"
#include "sim/World.h"
#include "tests/support/ModuleHarness.h"

namespace nao {
namespace {

using modules::FieldBallLocator;
using testing::ModuleHarness;

FieldDimensions standardField() { return FieldDimensions::load(dataPath("config/field_dimensions.json")); }

TEST(FieldBallLocator, TheDensestClusterAndItsNearObservations) {
  const FieldBallLocator::Params p;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> far(0, 0.06), near(0, 0.004);
  std::deque<FieldBallLocator::Observation> obs;
  double t = 0;
  // From afar: the ball at (-2, 1), noisy; a false ball at (-1, -2) a few times.
  for (int i = 0; i < 40; ++i) obs.push_back({Eigen::Vector2d(-2 + far(rng), 1 + far(rng)), 3.0, t += 0.03});
  for (int i = 0; i < 8; ++i) obs.push_back({Eigen::Vector2d(-1, -2), 2.0, t += 0.03});
  // From near: where the ball truly is, a centimetre from the far estimate's centre.
  for (int i = 0; i < 40; ++i) obs.push_back({Eigen::Vector2d(-2.01 + near(rng), 1.0 + near(rng)), 0.9, t += 0.03});
  const FieldBalls::Ball b = FieldBallLocator::estimate(obs, p);
  ASSERT_TRUE(b.seen);
  EXPECT_LT((b.position - Eigen::Vector2d(-2, 1)).norm(), 0.03);
  EXPECT_EQ(b.close, 40);
  EXPECT_LT((b.closePosition - Eigen::Vector2d(-2.01, 1.0)).norm(), 0.003);
  EXPECT_LT(b.closeSpread, 0.01);
  EXPECT_NEAR(b.lastSeen, t, 1e-12);
  // Too few observations are no ball.
  obs.resize(3);
  EXPECT_FALSE(FieldBallLocator::estimate(obs, p).seen);
}

TEST(FieldBallLocator, PerceptsBecomeFieldBallsPerHalfUntilANewStart) {
  ModuleHarness h = ModuleHarness::make<FieldBallLocator>();
  RobotPose pose;
  pose.valid = true;
  pose.covariance = Eigen::Matrix3d::Identity() * 1e-4;
  pose.pose = Pose2(-2, 0, M_PI / 2);  // facing +y
  CameraPercepts percepts;
  percepts.processed = true;
  percepts.ball.seen = true;
  percepts.ball.position = Eigen::Vector2d(1, 0);  // 1 m ahead: field (-2, 1)
  ChallengeMode mode;
  mode.modeId = 1;
  for (int i = 0; i < 10; ++i) {
    percepts.timestamp = 0.033 * i;
    h.fix(pose).fix(percepts).fix(mode).run();
  }
  FieldBalls balls = h.get<FieldBalls>();
  ASSERT_TRUE(balls.own.seen);
  EXPECT_FALSE(balls.opponent.seen);
  EXPECT_LT((balls.own.position - Eigen::Vector2d(-2, 1)).norm(), 1e-9);
  EXPECT_LT((balls.own.closePosition - Eigen::Vector2d(-2, 1)).norm(), 1e-9);
  // An uncertain pose adds nothing; a ball in the other half goes there.
  pose.pose = Pose2(1, 0, 0);
  pose.covariance = Eigen::Matrix3d::Identity();
  percepts.timestamp += 0.033;
  h.fix(pose).fix(percepts).fix(mode).run();
  EXPECT_EQ(h.get<FieldBalls>().own.support, 10);
  EXPECT_EQ(h.get<FieldBalls>().opponent.support, 0);
  pose.covariance = Eigen::Matrix3d::Identity() * 1e-4;
  for (int i = 0; i < 5; ++i) {
    percepts.timestamp += 0.033;
    h.fix(pose).fix(percepts).fix(mode).run();
  }
  EXPECT_TRUE(h.get<FieldBalls>().opponent.seen);
  EXPECT_LT((h.get<FieldBalls>().opponent.position - Eigen::Vector2d(2, 0)).norm(), 1e-9);
  // The referee starts again: both halves are empty.
  mode.modeId = 2;
  percepts.ball.seen = false;
  h.fix(pose).fix(percepts).fix(mode).run();
  EXPECT_FALSE(h.get<FieldBalls>().own.seen);
  EXPECT_FALSE(h.get<FieldBalls>().opponent.seen);
}

double segmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

TEST(ChallengeTasks, WalksGoRoundKnownBallsInsideTheField) {
  const FieldDimensions field = standardField();
  const behavior::ChallengeTasks::Params p;
  FieldBalls balls;
  const Eigen::Vector2d from(-4, 0), to(0, 0);
  EXPECT_EQ(behavior::ChallengeTasks::detour(from, to, balls, field, p), to);  // no ball known
  balls.own.seen = true;
  balls.own.position = Eigen::Vector2d(-2, 0.1);
  const Eigen::Vector2d w = behavior::ChallengeTasks::detour(from, to, balls, field, p);
  EXPECT_NEAR((w - balls.own.position).norm(), p.detourClearance, 1e-9);
  EXPECT_LT(w.y(), 0) << "round the side the straight way passes";
  EXPECT_GE(segmentDistance(balls.own.position, from, w), p.ballClearance);
  EXPECT_GE(segmentDistance(balls.own.position, w, to), p.ballClearance);
  // Gone round once on this walk, the ball does not make another detour from beside it.
  const std::vector<Eigen::Vector2d> passed{balls.own.position};
  EXPECT_EQ(behavior::ChallengeTasks::detour(w, Eigen::Vector2d(-1.5, 0), balls, field, p, passed), Eigen::Vector2d(-1.5, 0));
  // A ball passed at a distance needs no detour; one beside the side line is passed inside.
  balls.own.position = Eigen::Vector2d(-2, 0.6);
  EXPECT_EQ(behavior::ChallengeTasks::detour(from, to, balls, field, p), to);
  balls.own.position = Eigen::Vector2d(-2, 2.45);
  const Eigen::Vector2d in = behavior::ChallengeTasks::detour(Eigen::Vector2d(-4, 2.5), Eigen::Vector2d(0, 2.5), balls, field, p);
  EXPECT_LT(in.y(), 2.45);
  EXPECT_LE(std::abs(in.y()), field.width / 2 - p.fieldMargin);
  // The nearer of two balls on the way comes first.
  balls.opponent.seen = true;
  balls.opponent.position = Eigen::Vector2d(2, 0);
  balls.own.position = Eigen::Vector2d(-2, 0);
  EXPECT_LT(behavior::ChallengeTasks::detour(Eigen::Vector2d(-4, 0), Eigen::Vector2d(4, 0), balls, field, p).x(), 0);
}

// The walk to the own goal's centre from near the corner (seed 56 of the challenge rows: the
// straight way passed the right post 0.19 m off, the robot brushed it and fell against it). Every
// leg of the walk, waypoint after waypoint as the behaviour walks them, keeps postClearance
// from all four posts, and the walk ends at the goal centre.
TEST(ChallengeTasks, WalksGoRoundTheGoalPosts) {
  const FieldDimensions field = standardField();
  const behavior::ChallengeTasks::Params p;
  const FieldBalls noBalls;
  const double postY = field.goalInnerWidth / 2 + field.goalPostDiameter / 2;
  std::vector<Eigen::Vector2d> posts;
  for (const double x : {-field.length / 2, field.length / 2})
    for (const double y : {-postY, postY}) posts.emplace_back(x, y);
  const Eigen::Vector2d goalCentre(-field.length / 2, 0);
  for (const Eigen::Vector2d& start : {Eigen::Vector2d(-3.84, -2.68), Eigen::Vector2d(-4.1, 2.9), Eigen::Vector2d(-4.2, -1.2),
                                      Eigen::Vector2d(-2, 0.5), Eigen::Vector2d(3.9, 2.5)}) {
    const Eigen::Vector2d to = start.x() < 0 ? goalCentre : -goalCentre;
    SCOPED_TRACE(::testing::Message() << "from " << start.transpose());
    Eigen::Vector2d here = start, obstacle;
    std::vector<Eigen::Vector2d> passed;
    int legs = 0;
    while (here != to && legs < 5) {
      const Eigen::Vector2d next = behavior::ChallengeTasks::detour(here, to, noBalls, field, p, passed, &obstacle);
      for (const Eigen::Vector2d& post : posts)
        EXPECT_GE(segmentDistance(post, here, next), p.postClearance - 1e-9) << "leg " << legs << " to " << next.transpose();
      if (next != to) passed.push_back(obstacle);
      here = next;
      ++legs;
    }
    EXPECT_EQ(here, to);
  }
  EXPECT_LT(segmentDistance(posts[0], Eigen::Vector2d(-3.84, -2.68), goalCentre), 0.2) << "the case needs a detour";
  // A way in front of the goal passes the posts without one.
  EXPECT_EQ(behavior::ChallengeTasks::detour(Eigen::Vector2d(0, 0), goalCentre, noBalls, field, p), goalCentre);
}

// Phase 1's first decision: which side line the robot starts on. The own goal box seen to the
// right means the left side line, whatever the (uncalibrated) localization believes; without a
// sighting the localization decides after sideTimeout.
TEST(CalibrateCameras, TheGoalBoxInViewDecidesTheStartSide) {
  const BallModel ball;
  const GameState game;
  const FallState fall;
  const MotionInfo motion;
  const BehaviorCommand command;
  const CalibrationStatus status;
  const CameraCalibration current;
  auto decide = [&](std::optional<double> boxLateral, double believedY, double seconds, double believedX = -3.2) {
    behavior::CalibrateCameras c(standardField(), StandController::standPosture(), {});
    c.restart(0);
    RobotPose pose;
    pose.valid = true;
    pose.pose = Pose2(believedX, believedY, believedY > 0 ? -M_PI / 2 : M_PI / 2);
    CameraPercepts p;
    p.processed = true;
    if (boxLateral) {
      // The short line 2 m ahead, square to the view; the long lines run away from it.
      auto line = [&](double x0, double y0, double x1, double y1) {
        LinesPercept::Line l;
        l.imageFrom = l.imageTo = Eigen::Vector2d::Zero();
        l.from = Eigen::Vector2d(x0, y0);
        l.to = Eigen::Vector2d(x1, y1);
        p.lines.push_back(l);
      };
      line(2.0, *boxLateral - 0.3, 2.0, *boxLateral + 0.3);
      line(2.0, *boxLateral - 0.3, 3.0, *boxLateral - 0.3);
      line(2.0, *boxLateral + 0.3, 3.0, *boxLateral + 0.3);
      p.goalBoxSide = {true, 0, 1, 2};
    }
    behavior::CalibrateCameras::Output out;
    for (double t = 0; t <= seconds; t += 1.0 / 30) {
      p.timestamp = t;
      const behavior::BehaviorInput in{t, pose, ball, game, fall, motion, command};
      out = c.run(in, status, current, p);
      if (c.state() != behavior::CalibrateCameras::State::Localize) break;
    }
    return std::make_pair(c.summary().side, c.summary().sideFrom);
  };
  // The box to the right: the left side line, though the localization holds the mirror.
  EXPECT_EQ(decide(-0.9, -3.0, 2.0), std::make_pair(1, std::string("goal box")));
  EXPECT_EQ(decide(0.9, 3.0, 2.0), std::make_pair(-1, std::string("goal box")));
  // Nothing seen: nothing decided before the timeout, the localization after it.
  EXPECT_EQ(decide(std::nullopt, 3.0, 3.0).first, 0);
  EXPECT_EQ(decide(std::nullopt, 3.0, 5.0), std::make_pair(1, std::string("localization")));
  EXPECT_EQ(decide(std::nullopt, -3.0, 5.0), std::make_pair(-1, std::string("localization")));
  // A box straight ahead says nothing.
  EXPECT_EQ(decide(0.0, -3.0, 5.0), std::make_pair(-1, std::string("localization")));
  // A pose in the other half is the point mirror of the start (the rules start the robot in its
  // own half): (2.66, 3.19) facing -y means (-2.66, -3.19) facing +y, the right side line.
  EXPECT_EQ(decide(std::nullopt, 3.19, 5.0, 2.66), std::make_pair(-1, std::string("localization")));
  EXPECT_EQ(decide(std::nullopt, -3.0, 5.0, 3.2), std::make_pair(1, std::string("localization")));
}

// The far views (CalibrateCameras::Params::farDistance): after the planned views at the
// calibration position the robot steps back to farDistance from the box's short line and takes
// farPans pans with each camera; each view's walk target is that place, facing where the plan
// says. Without them the plan is the ten views in place, as before.
TEST(CalibrateCameras, TheFarViewsAreTakenFromTheFarDistance) {
  const BallModel ball;
  const GameState game;
  const FallState fall;
  MotionInfo motion;
  motion.walkToReached = true;  // every walk arrives at once
  const BehaviorCommand command;
  const CalibrationStatus status;  // no view answered: each one times out
  const CameraCalibration current;
  const FieldDimensions field = standardField();
  auto run = [&](double farDistance) {
    behavior::CalibrateCameras::Params params;
    params.farDistance = farDistance;
    behavior::CalibrateCameras c(field, StandController::standPosture(), params);
    c.restart(0);
    RobotPose pose;
    pose.valid = true;
    pose.pose = Pose2(-3.2, -3.0, M_PI / 2);  // believed on the right side line; odometry at identity
    CameraPercepts p;
    p.processed = true;
    std::vector<Pose2> targets;  // each view's walk target (odometry frame = field frame from the start here)
    for (double t = 0; t <= 120 && c.state() != behavior::CalibrateCameras::State::Solve; t += 1.0 / 30) {
      p.timestamp = t;
      const behavior::BehaviorInput in{t, pose, ball, game, fall, motion, command};
      const auto out = c.run(in, status, current, p);
      if (c.state() == behavior::CalibrateCameras::State::Collect && out.calibration.viewId > 0 &&
          (targets.size() < static_cast<std::size_t>(out.calibration.viewId)))
        targets.push_back(out.motion.walkTarget);
    }
    return std::make_pair(c.summary().views, targets);
  };
  const auto [nearOnly, nearTargets] = run(0);
  EXPECT_EQ(nearOnly, 10);
  const auto [withFar, targets] = run(1.8);
  ASSERT_EQ(withFar, 16);
  ASSERT_EQ(targets.size(), 16u);
  // The robot never moved and its odometry is the identity, so the targets are relative to the
  // start (-3.2, -3, 90 deg), from where the views were planned (it saw no short line to align on).
  const Pose2 start(calibration::initialPosition(field, -1).x(), calibration::initialPosition(field, -1).y(),
                    calibration::initialPosition(field, -1).z());
  const calibration::GoalBoxSide side = calibration::ownGoalBoxSide(field, -1);
  const double nearDistance = (start.translation() - side.middle()).norm();
  for (int k = 0; k < 16; ++k) {
    const Pose2 at = start * targets[k];
    const double d = (at.translation() - side.middle()).norm();
    EXPECT_NEAR(d, k < 10 ? nearDistance : 1.8, 1e-6) << "view " << k + 1;
    if (k < 10) {
      EXPECT_NEAR(targets[k].translation().norm(), 0, 1e-9) << "the near views turn in place";
    }
  }
  // The far place lies on the line from the short line's middle through the near one.
  const Eigen::Vector2d awayNear = (start.translation() - side.middle()).normalized();
  const Eigen::Vector2d awayFar = ((start * targets[12]).translation() - side.middle()).normalized();
  EXPECT_NEAR(awayNear.dot(awayFar), 1, 1e-9);
}

// Lost, the robot stands for lostTurnAfter, then turns in place (the head sweeping, by
// LookActive) until the pose is valid again; then it walks to its target as before. A robot of
// challenge seed 8 stood lost for 500 s, seeing the same features the whole time.
TEST(GoToPose, ALostRobotStandsThenTurnsInPlace) {
  const BallModel ball;
  const GameState game;
  const FallState fall;
  const MotionInfo motion;
  const BehaviorCommand command;
  behavior::GoToPose::Params params;
  params.lostTurnAfter = 6;
  params.lostTurnSpeed = 0.4;
  behavior::GoToPose goTo(params);
  RobotPose pose;
  pose.pose = Pose2(-2, -1, 2.4);
  const Pose2 target(-4.5, 0, 0);
  auto at = [&](double t, bool valid) {
    pose.valid = valid;
    const behavior::BehaviorInput in{t, pose, ball, game, fall, motion, command};
    MotionRequest r;
    goTo.run(in, target, r);
    return r;
  };
  MotionRequest r = at(0, true);
  EXPECT_EQ(r.motion, MotionType::WalkTo);
  r = at(1, false);  // lost at 1 s
  EXPECT_EQ(r.motion, MotionType::Stand);
  r = at(6.9, false);
  EXPECT_EQ(r.motion, MotionType::Stand);
  r = at(7.0, false);
  EXPECT_EQ(r.motion, MotionType::Walk);
  EXPECT_EQ(r.walkSpeed.x, 0);
  EXPECT_EQ(r.walkSpeed.y, 0);
  EXPECT_NEAR(r.walkSpeed.theta, 0.4, 1e-12);
  r = at(30, false);
  EXPECT_EQ(r.motion, MotionType::Walk);
  r = at(31, true);  // found again: to the target
  EXPECT_EQ(r.motion, MotionType::WalkTo);
  r = at(32, false);  // lost anew: the wait starts over
  EXPECT_EQ(r.motion, MotionType::Stand);
  r = at(37.5, false);
  EXPECT_EQ(r.motion, MotionType::Stand);
  r = at(38.1, false);
  EXPECT_EQ(r.motion, MotionType::Walk);
  // lostTurnAfter 0: it stands however long it is lost.
  params.lostTurnAfter = 0;
  behavior::GoToPose standing(params);
  pose.valid = false;
  MotionRequest s;
  for (double t = 0; t < 60; t += 1) {
    const behavior::BehaviorInput in{t, pose, ball, game, fall, motion, command};
    standing.run(in, target, s);
  }
  EXPECT_EQ(s.motion, MotionType::Stand);
}

TEST(ChallengeTasks, TheBallSentenceInMillimetres) {
  EXPECT_EQ(behavior::ballReport(Eigen::Vector2d(1.2345, -0.0004)), "The ball is at: 1235 0");
  EXPECT_EQ(behavior::ballReport(Eigen::Vector2d(-0.12, 2.7)), "The ball is at: -120 2700");
  const behavior::ChallengeTasks tasks(standardField(), {});
  using T = behavior::ChallengeTasks::Task;
  EXPECT_EQ(tasks.spot(T::WalkOwnGoal).x, -4.5);
  EXPECT_EQ(tasks.spot(T::WalkCenter).x, 0);
  EXPECT_EQ(tasks.spot(T::WalkOpponentGoal).x, 4.5);
  // The referee reads what the robot says back into metres, and nothing else.
  const auto heard = sim::parseBallSentence(behavior::ballReport(Eigen::Vector2d(-0.12, 2.7)));
  ASSERT_TRUE(heard);
  EXPECT_NEAR(heard->x(), -0.12, 1e-12);
  EXPECT_NEAR(heard->y(), 2.7, 1e-12);
  for (const char* bad : {"The ball is at: 12", "The ball is at: 1.5 2", "The ball is at: 1 2 3", "The ball is at: - 2",
                          "the ball is at: 1 2", "The ball is at: 1  2", "The ball is at: 1 2 ", "The ball is at: 9999999999 1"})
    EXPECT_FALSE(sim::parseBallSentence(bad)) << bad;
}

TEST(ChallengeBalls, DrawnClearOfLinesSpotsAndTheStart) {
  const FieldDimensions field = standardField();
  const FieldModel model = FieldModel::from(field);
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    const int side = seed % 2 ? 1 : -1;
    const auto balls = sim::phaseTwoBalls(field, seed, side);
    ASSERT_NO_THROW(sim::checkBalls(field, balls, "draw"));
    EXPECT_LT(balls[0].x(), -0.3 + 1e-9);
    EXPECT_GT(balls[1].x(), 0.3 - 1e-9);
    const Eigen::Vector2d start = calibration::initialPosition(field, side).head<2>();
    for (const Eigen::Vector2d& b : balls) {
      EXPECT_LE(std::abs(b.x()), field.length / 2 - 0.3 + 1e-9);
      EXPECT_LE(std::abs(b.y()), field.width / 2 - 0.3 + 1e-9);
      EXPECT_GE((b - start).norm(), 0.6);
      for (const Eigen::Vector2d& s : {Eigen::Vector2d(-4.5, 0), Eigen::Vector2d(0, 0), Eigen::Vector2d(4.5, 0)})
        EXPECT_GE((b - s).norm(), 0.6);
      for (const FieldLine& l : model.lines) EXPECT_GE(segmentDistance(b, l.from, l.to), 0.15) << l.name;
      EXPECT_GE(std::abs(b.norm() - model.centerCircleRadius), 0.15);
    }
    EXPECT_EQ(sim::phaseTwoBalls(field, seed, side), balls) << "the same seed, the same balls";
  }
  EXPECT_NE(sim::phaseTwoBalls(field, 1, 1), sim::phaseTwoBalls(field, 2, 1));
}

TEST(ChallengeBalls, BallsOffTheFieldOrOnALineAreRefused) {
  const FieldDimensions field = standardField();
  auto error = [&](const std::array<Eigen::Vector2d, 2>& balls) {
    try {
      sim::checkBalls(field, balls, "venue.json");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error({Eigen::Vector2d(-2, 1), Eigen::Vector2d(2, -1)}), "");
  EXPECT_EQ(error({Eigen::Vector2d(-2, 3.2), Eigen::Vector2d(2, -1)}), "venue.json: the own half's ball lies outside the field");
  EXPECT_EQ(error({Eigen::Vector2d(-2, 1), Eigen::Vector2d(4.5, 1)}), "venue.json: the opponent half's ball lies on a line");
  EXPECT_EQ(error({Eigen::Vector2d(2, 1), Eigen::Vector2d(2, -1)}), "venue.json: the own half's ball lies in the other half");
  EXPECT_EQ(error({Eigen::Vector2d(-2, NAN), Eigen::Vector2d(2, -1)}), "venue.json: the own half's ball lies outside the field");
}

TEST(ChallengeVenues, TheCommittedVenuesKeepTheDrawsRules) {
  const FieldDimensions field = standardField();
  const FieldModel model = FieldModel::from(field);
  const std::vector<sim::Venue> venues = sim::loadVenues(dataPath("config/venues.json"), field);
  ASSERT_GE(venues.size(), 3u) << "the rules average over at least three venues";
  for (const sim::Venue& v : venues) {
    for (const Eigen::Vector2d& b : v.balls) {
      for (const FieldLine& l : model.lines) EXPECT_GE(segmentDistance(b, l.from, l.to), 0.15) << v.name << " " << l.name;
      EXPECT_GE(std::abs(b.norm() - model.centerCircleRadius), 0.15) << v.name;
      for (const Eigen::Vector2d& c : model.penaltyCrosses) EXPECT_GE((b - c).norm(), 0.15) << v.name;
      for (const Eigen::Vector2d& s : {Eigen::Vector2d(-4.5, 0), Eigen::Vector2d(0, 0), Eigen::Vector2d(4.5, 0),
                                       Eigen::Vector2d(calibration::initialPosition(field, 1).head<2>()),
                                       Eigen::Vector2d(calibration::initialPosition(field, -1).head<2>())})
        EXPECT_GE((b - s).norm(), 0.6) << v.name;
    }
    EXPECT_GE((v.balls[0] - v.balls[1]).norm(), 0.6) << v.name;
  }
  EXPECT_EQ(sim::venueNamed(venues, "hall-b").name, "hall-b");
  EXPECT_THROW(sim::venueNamed(venues, "hall-z"), Error);
}

TEST(ChallengeVenues, ABadVenueFileNamesTheFileAndTheKey) {
  const FieldDimensions field = standardField();
  const std::string path = ::testing::TempDir() + "/venues.json";
  auto error = [&](const std::string& text) {
    std::ofstream(path) << text;
    try {
      sim::loadVenues(path, field);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string good = R"({"name": "x", "floor_friction": 0.8, "balls": [[-2, 1], [2, -1]]})";
  EXPECT_EQ(error(R"({"venues": [)" + good + "]}"), "");
  EXPECT_EQ(error(R"({"venues": [{"name": "x", "floor_friction": 0.8, "balls": [[-2, 3.5], [2, -1]]}]})"),
            path + ": venues[0].balls: the own half's ball lies outside the field");
  EXPECT_EQ(error(R"({"venues": [{"name": "x", "floor_friction": 0.8, "balls": [[-2, 1], [-1, 1.2]]}]})"),
            path + ": venues[0].balls: the opponent half's ball lies in the other half");
  EXPECT_EQ(error(R"({"venues": [{"name": "x", "floor_friction": 5, "balls": [[-2, 1], [2, -1]]}]})"),
            path + ": venues[0].floor_friction: must be a number in 0.2..2");
  EXPECT_EQ(error(R"({"venues": [{"name": "x", "floor_friction": 0.8, "balls": [[-2, 1]]}]})"),
            path + ": venues[0].balls: must be two [x, y] pairs (own half, opponent half)");
  EXPECT_EQ(error(R"({"venues": [)" + good + "," + good + "]}"), path + ": venues[1].name: \"x\" is there twice");
  EXPECT_EQ(error(R"({"venues": [{"name": "x", "floor_friction": 0.8, "balls": [[-2, 1], [2, -1]], "ball": 1}]})"),
            path + ": venues[0].ball: unknown key");
  EXPECT_EQ(error(R"({"venues": [)").rfind(path + ": not valid JSON: parse error at line 1", 0), 0u);
  EXPECT_EQ(error(R"({"venues": []})"), path + ": venues: must be a non-empty array");
}

TEST(ChallengeScoring, TheRefereesRounding) {
  EXPECT_DOUBLE_EQ(sim::roundTo(0.049, 0.1), 0.0);
  EXPECT_DOUBLE_EQ(sim::roundTo(0.051, 0.1), 0.1);
  EXPECT_DOUBLE_EQ(sim::roundTo(62.4, 5), 60);
  EXPECT_DOUBLE_EQ(sim::roundTo(62.6, 5), 65);
}

// A world with the robot standing at `pose` and two balls far away (truth only: no program).
struct RefereeWorld {
  sim::World world;
  sim::ChallengeReferee referee;
  std::vector<sim::ChallengeEvent> events;
  explicit RefereeWorld(const Eigen::Vector3d& pose) : world(spec(pose), 1) {
    world.placeRobot(0, pose, StandController::standPosture());
  }
  static sim::SceneSpec spec(const Eigen::Vector3d& pose) {
    sim::SceneSpec s;
    s.field = standardField();
    s.robots = {pose};
    s.balls = {Eigen::Vector3d(-2, 2, 0.05), Eigen::Vector3d(2, -2, 0.05)};
    return s;
  }
  std::string run(double seconds) {
    const double end = world.time() + seconds;
    while (world.time() < end && referee.terminated().empty()) {
      world.stepCycle();
      referee.check(world, 0, events);
    }
    return referee.terminated();
  }
  int count(const std::string& kind) const {
    return static_cast<int>(std::count_if(events.begin(), events.end(), [&](const auto& e) { return e.kind == kind; }));
  }
};

TEST(ChallengeReferee, ABallRolledIntoTheFeetIsTouched) {
  RefereeWorld r(Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(r.run(1.0), "") << "standing with the balls far away";
  // A ball at rest 0.3 m ahead is not touched ...
  r.world.placeBall(0, Eigen::Vector3d(0.3, 1, 0.05));
  EXPECT_EQ(r.run(1.0), "");
  // ... one rolled into the feet from the side is, within the step it arrives.
  r.world.placeBall(1, Eigen::Vector3d(0.03, 1.6, 0.05), Eigen::Vector3d(0, -1.5, 0));
  EXPECT_EQ(r.run(2.0), "touched_ball");
  ASSERT_EQ(r.count("ball_contact"), 1);
  EXPECT_EQ(r.count("termination"), 1);
  EXPECT_NE(r.events.front().text.find("ball 1"), std::string::npos) << r.events.front().text;
}

TEST(ChallengeReferee, LeavingTheFieldIsBothSolesBeyondTheLine) {
  const FieldDimensions f = standardField();
  for (const auto& [pose, out] : std::vector<std::pair<Eigen::Vector3d, bool>>{
           {Eigen::Vector3d(0, f.width / 2, 0), false},            // on the side line
           {Eigen::Vector3d(-f.length / 2, 0, 0), false},          // on the goal line (the own goal's centre)
           {Eigen::Vector3d(0, f.width / 2 + 0.12, 0), false},     // a sole's edge still on the line
           {Eigen::Vector3d(0, f.width / 2 + 0.3, 0), true},
           {Eigen::Vector3d(f.length / 2 + 0.3, 1, M_PI / 2), true}}) {
    RefereeWorld r(pose);
    EXPECT_EQ(sim::ChallengeReferee::leftField(r.world, 0), out) << pose.transpose();
    EXPECT_EQ(r.run(0.1), out ? "left_field" : "") << pose.transpose();
  }
}

// The report's arm: a standing robot with a hand above its head. A robot on the ground is not
// reporting, wherever its hands are (seed 56's get-up tries were logged as arm raises).
TEST(ChallengeReferee, AnArmIsRaisedOnlyByAStandingRobot) {
  const Eigen::Vector3d pose(0, 0, 0);
  RefereeWorld r(pose);
  EXPECT_FALSE(r.referee.armRaised(r.world, 0)) << "standing, arms down";
  JointArray up = StandController::standPosture();
  up[RShoulderPitch] = -1.5;  // the right arm up in front
  r.world.placeRobot(0, pose, up);
  EXPECT_TRUE(r.referee.armRaised(r.world, 0));
  // The same hand above the head, but the torso further from upright than the referee's
  // "standing" (here: a referee for whom nothing stands): no arm raised.
  sim::ChallengeReferee::Params strict;
  strict.upTilt = -1;
  EXPECT_FALSE(sim::ChallengeReferee(strict).armRaised(r.world, 0));
  // Pushed over: none either.
  r.world.pushRobot(0, Eigen::Vector3d(-12, 0, 0));
  r.run(3.0);
  ASSERT_EQ(r.referee.falls(), 1);
  EXPECT_FALSE(r.referee.armRaised(r.world, 0));
}

TEST(ChallengeReferee, ThreeFallsAndAFallWithoutGettingUp) {
  RefereeWorld r(Eigen::Vector3d(0, 0, 0));
  for (int fall = 1; fall <= 3; ++fall) {
    r.world.pushRobot(0, Eigen::Vector3d(12, 0, 0));
    r.run(3.0);
    EXPECT_EQ(r.referee.falls(), fall);
    if (fall < 3) {
      EXPECT_EQ(r.referee.terminated(), "");
      r.world.placeRobot(0, Eigen::Vector3d(0, 0, 0), StandController::standPosture());
      r.referee.placed();
      r.run(1.0);
    }
  }
  EXPECT_EQ(r.referee.terminated(), "three_falls");
  // No robot program: the pushed robot lies there.
  RefereeWorld lying(Eigen::Vector3d(0, 0, 0));
  lying.world.pushRobot(0, Eigen::Vector3d(12, 0, 0));
  EXPECT_EQ(lying.run(59.0), "");
  EXPECT_EQ(lying.referee.falls(), 1);
  EXPECT_EQ(lying.run(3.0), "not_up_within_60s");
}

}  // namespace
}  // namespace nao
