// The 1vs1 striker option (controllers/behavior/Striker.h) on scripted inputs: what it asks of
// the body in each game state, where it walks to kick, when it kicks, and that it keeps off the
// halfway line; the scripted baseline player (`match --opponent baseline`) does neither.
#include <gtest/gtest.h>

#include <cmath>

#include "controllers/behavior/Striker.h"

namespace {

using nao::MotionType;
using nao::Pose2;
using nao::behavior::Striker;

struct Inputs {
  nao::RobotPose pose;
  nao::BallModel ball;
  nao::GameState game;
  nao::FallState fall;
  nao::MotionInfo motion;
  nao::BehaviorCommand command;
  double time = 10;

  Inputs() {
    game.fromGameController = true;
    game.state = nao::gc::State::Playing;
    pose.valid = true;
  }
  nao::behavior::BehaviorInput in() const { return {time, pose, ball, game, fall, motion, command}; }
  // The robot at `robot` (field) and a ball seen now at `field` (field).
  void place(const Pose2& robot, const Eigen::Vector2d& field) {
    pose.pose = robot;
    pose.odometry = robot;  // the odometry frame equal to the field frame
    ball.valid = ball.fieldValid = true;
    ball.seenTime = time;
    ball.fieldPosition = field;
    ball.position = robot.inverse() * field;
  }
};

TEST(Striker, StandsWithoutAGameControllerOrWhenPenalisedAndPositionsInReady) {
  Striker s(nao::FieldDimensions{}, {});
  Inputs i;
  i.place(Pose2(-2, 0, 0), {-1, 0});
  nao::MotionRequest m;
  i.game.fromGameController = false;
  s.run(i.in(), m);
  EXPECT_EQ(s.state(), Striker::State::Stand);
  EXPECT_EQ(m.motion, MotionType::Stand);
  i.game.fromGameController = true;
  i.game.penalty = nao::gc::Penalty::InactivePlayer;
  s.run(i.in(), m);
  EXPECT_EQ(m.motion, MotionType::Stand);
  i.game.penalty = nao::gc::Penalty::None;
  i.game.state = nao::gc::State::Set;
  s.run(i.in(), m);
  EXPECT_EQ(m.motion, MotionType::Stand);
  i.game.state = nao::gc::State::Ready;
  s.run(i.in(), m);
  EXPECT_EQ(s.state(), Striker::State::Position);
  ASSERT_EQ(m.motion, MotionType::WalkTo);
  EXPECT_NEAR(m.walkTarget.x, -4.2, 1e-9);  // the ready pose, odometry frame = field frame here
  EXPECT_NEAR(m.walkTarget.y, 0.0, 1e-9);
}

TEST(Striker, SearchesWithoutABallThenWalksBehindItAndKicks) {
  Striker::Params shortKick;
  shortKick.kick.travel = 3.2;  // the goal out of reach: a straight ball-in-half kick
  Striker s(nao::FieldDimensions{}, shortKick);
  Inputs i;
  nao::MotionRequest m;
  i.pose.pose = i.pose.odometry = Pose2(-2, 0, 0);
  s.run(i.in(), m);
  EXPECT_EQ(s.state(), Striker::State::Search);
  EXPECT_EQ(m.motion, MotionType::Walk);
  EXPECT_GT(m.walkSpeed.theta, 0);
  // The ball at (-1, 0.3): kicked straight on (it stops in the other half), so the robot goes to
  // 0.16 m behind it with the ball in front of its left foot.
  i.place(Pose2(-2, 0, 0), {-1, 0.3});
  s.run(i.in(), m);
  EXPECT_EQ(s.state(), Striker::State::Approach);
  ASSERT_EQ(m.motion, MotionType::WalkTo);
  EXPECT_NEAR(s.lastChoice().direction, 0, 1e-9);
  EXPECT_NEAR(m.walkTarget.x, -1.16, 1e-9);
  EXPECT_NEAR(m.walkTarget.y, 0.25, 1e-9);
  // There: the kick starts once and runs until the motion says it is done.
  i.place(Pose2(-1.16, 0.25, 0.02), {-1, 0.3});
  s.run(i.in(), m);
  EXPECT_EQ(s.state(), Striker::State::Kick);
  ASSERT_EQ(m.motion, MotionType::Kick);
  const int id = m.kickId;
  EXPECT_NEAR(m.kickDirection, -0.02, 1e-9);
  i.time += 0.5;
  i.ball.position = {0.3, 0.05};  // the ball leaves the foot
  s.run(i.in(), m);
  EXPECT_EQ(m.motion, MotionType::Kick);
  EXPECT_EQ(m.kickId, id);
  // Nudged towards the halfway line while the engine walked: too near it to kick now.
  {
    Striker near(nao::FieldDimensions{}, {});
    Inputs k;
    nao::MotionRequest mk;
    k.place(Pose2(-0.5, 0.0, 0.0), {-0.34, 0.05});
    near.run(k.in(), mk);
    ASSERT_EQ(near.state(), Striker::State::Kick);
    k.place(Pose2(-0.5, 0.0, 0.0), {-0.12, 0.05});
    k.time += 0.3;
    near.run(k.in(), mk);
    EXPECT_NE(near.state(), Striker::State::Kick);
    EXPECT_NE(mk.motion, MotionType::Kick);
  }
  i.motion.kickDone = true;
  i.ball.rolling = true;  // on its way to the other half
  i.ball.fieldEndPosition = {2.0, 0.3};
  i.time += 0.5;
  s.run(i.in(), m);
  EXPECT_NE(s.state(), Striker::State::Kick);
  EXPECT_EQ(s.kicks(), 1);
}

// A ball that stopped just in front of the own goal (the opponent's long kicks): the robot
// never walks into the goal or over the end line to kick it; it kicks at an angle from the field.
TEST(Striker, ABallAtTheOwnGoalLineIsKickedFromTheField) {
  const Striker::Params p;
  const double minX = -4.5 + p.endLineClearance;
  for (const Eigen::Vector2d& ball : {Eigen::Vector2d(-4.42, 0.3), Eigen::Vector2d(-4.4, -0.6), Eigen::Vector2d(-4.35, 1.5)}) {
    for (const Pose2& from : {Pose2(-3, 0, 0), Pose2(-4.0, 1.0, -M_PI / 2), Pose2(-3.5, -1.5, M_PI)}) {
      Striker s(nao::FieldDimensions{}, p);
      Inputs i;
      nao::MotionRequest m;
      i.place(from, ball);
      s.run(i.in(), m);
      ASSERT_EQ(m.motion, MotionType::WalkTo) << ball.transpose();
      // The walk target is in the field frame here (odometry = field pose).
      EXPECT_GE(m.walkTarget.x, minX - 1e-9) << ball.transpose() << " from " << from.x << ", " << from.y;
      // The kick's own pose is on the field, and the kick still goes away from the own goal.
      const double d = s.lastChoice().direction;
      const Eigen::Vector2d pose = ball - Eigen::Vector2d(std::cos(d) * p.kickBallX - std::sin(d) * p.kickBallY,
                                                         std::sin(d) * p.kickBallX + std::cos(d) * p.kickBallY);
      EXPECT_GE(pose.x(), minX - 1e-9) << ball.transpose();
      EXPECT_LE(std::abs(d), M_PI / 2 + 1e-9) << ball.transpose();
    }
  }
  // Further out the kick is the chosen one (no turn): a ball at x = -3.9 is kicked straight on.
  Striker s(nao::FieldDimensions{}, p);
  Inputs i;
  nao::MotionRequest m;
  i.place(Pose2(-3, 0, 0), {-3.9, 0.0});
  s.run(i.in(), m);
  EXPECT_NE(s.lastChoice().kind, nao::behavior::KickChoice::Kind::Advance);
}

TEST(Striker, ScansTheOwnHalfWhenNoKnownBallIsInReach) {
  Striker s(nao::FieldDimensions{}, {});
  Inputs i;
  nao::MotionRequest m;
  // In the other half, or too near the halfway line to kick without touching it.
  for (const Eigen::Vector2d& ball : {Eigen::Vector2d(1.0, 1.0), Eigen::Vector2d(-0.1, 0)}) {
    i.place(Pose2(-1, 1, 0), ball);
    s.run(i.in(), m);
    EXPECT_EQ(s.state(), Striker::State::Wait) << ball.transpose();
    ASSERT_EQ(m.motion, MotionType::WalkTo);  // to the middle of the own half ...
    EXPECT_NEAR(m.walkTarget.x, -1.8, 1e-9);
    EXPECT_NEAR(m.walkTarget.y, 0, 1e-9);
  }
  i.place(Pose2(-1.8, 0.1, 0), {1.0, 1.0});
  s.run(i.in(), m);
  EXPECT_EQ(m.motion, MotionType::Walk);  // ... and there it turns, looking over the own half
  EXPECT_GT(m.walkSpeed.theta, 0);
  EXPECT_EQ(m.walkSpeed.x, 0);
  // A ball a little further back can be played: the kick pose stays 0.3 m short of the line.
  i.place(Pose2(-2, 0, 0), {-0.3, 0});
  s.run(i.in(), m);
  EXPECT_EQ(s.state(), Striker::State::Approach);
  EXPECT_LE(m.walkTarget.x, -0.025 - 0.3);
  // A walk that overshot towards the line: whatever it wanted, it steps back first (field -x,
  // facing sideways here).
  i.place(Pose2(-0.25, 0, M_PI / 2), {-0.4, 0.2});
  s.run(i.in(), m);
  ASSERT_EQ(m.motion, MotionType::Walk);
  EXPECT_NEAR(m.walkSpeed.x, 0, 1e-9);
  EXPECT_GT(m.walkSpeed.y, 0);  // its left is field -x
}

// Four balls known (the tracks the BallTracker keeps): the nearest one in reach is the one, and
// the choice holds until another is clearly nearer; balls off the field do not count.
TEST(Striker, ChoosesTheNearestBallInReachAndKeepsItsChoice) {
  Striker s(nao::FieldDimensions{}, {});
  Inputs i;
  nao::MotionRequest m;
  i.pose.pose = i.pose.odometry = Pose2(-2.5, -1.0, M_PI);
  nao::BallTracks balls;
  for (const Eigen::Vector2d& at : {Eigen::Vector2d(-3.9, -1.1), Eigen::Vector2d(-3.9, 1.1), Eigen::Vector2d(3.9, -1.1),
                                    Eigen::Vector2d(-2.5, -3.5)}) {
    nao::BallTracks::Track t;
    t.position = at;
    balls.tracks.push_back(t);
  }
  s.run(i.in(), balls, m);
  EXPECT_EQ(s.state(), Striker::State::Approach);
  ASSERT_TRUE(s.lookAt());  // the ball model follows none: the head looks at the chosen one
  const Eigen::Vector2d chosen = i.pose.pose * *s.lookAt();
  EXPECT_LT((chosen - Eigen::Vector2d(-3.9, -1.1)).norm(), 1e-9);
  // Coming from in front of it: round it, by a point behind it (further from the goal it attacks).
  ASSERT_EQ(m.motion, MotionType::WalkTo);
  EXPECT_LT(m.walkTarget.x, -3.9);
  // Half-way to the other own-half ball the choice holds (the other is nearer, not clearly).
  i.pose.pose = i.pose.odometry = Pose2(-3.0, 0.1, M_PI);
  s.run(i.in(), balls, m);
  EXPECT_LT((i.pose.pose * *s.lookAt() - Eigen::Vector2d(-3.9, -1.1)).norm(), 1e-9);
  i.pose.pose = i.pose.odometry = Pose2(-3.0, 0.8, M_PI);
  s.run(i.in(), balls, m);
  EXPECT_LT((i.pose.pose * *s.lookAt() - Eigen::Vector2d(-3.9, 1.1)).norm(), 1e-9);
  // Only balls out of reach or off the field: it scans.
  balls.tracks.erase(balls.tracks.begin(), balls.tracks.begin() + 2);
  s.run(i.in(), balls, m);
  EXPECT_EQ(s.state(), Striker::State::Wait);
}

// The baseline walks to the ball wherever it lies, the other half too, and kicks it at the goal's
// centre.
TEST(Striker, TheBaselineKicksAtTheGoalCentreFromAnywhere) {
  Striker::Params params;
  params.player = "baseline";
  const nao::FieldDimensions field;
  Striker s(field, params);
  Inputs i;
  nao::MotionRequest m;
  const Eigen::Vector2d ball(1.0, 1.0);  // in the opponent half: the striker would wait
  i.place(Pose2(-2, 0, 0), ball);
  s.run(i.in(), m);
  EXPECT_EQ(s.state(), Striker::State::Approach);
  ASSERT_EQ(m.motion, MotionType::WalkTo);
  const double direction = std::atan2(0 - ball.y(), field.length / 2 - ball.x());
  EXPECT_NEAR(s.lastChoice().direction, direction, 1e-9);
  EXPECT_GT(m.walkTarget.x, 0.5) << "it crosses the halfway line";
  // Behind the ball on the goal line: it kicks.
  const double c = std::cos(direction), sn = std::sin(direction);
  const Eigen::Vector2d at = ball - Eigen::Vector2d(c * params.kickBallX - sn * params.kickBallY, sn * params.kickBallX + c * params.kickBallY);
  i.place(Pose2(at.x(), at.y(), direction), ball);
  s.run(i.in(), m);
  EXPECT_EQ(s.state(), Striker::State::Kick);
  EXPECT_EQ(m.motion, MotionType::Kick);
}

}  // namespace
