// The BallTracker module (controllers/modules/BallTracker.h) in the module harness: every ball
// the robot knows on the field, from percepts made at known field positions.
#include <gtest/gtest.h>

#include <cmath>

#include "controllers/modules/BallTracker.h"
#include "robot/Paths.h"
#include "tests/support/ModuleHarness.h"

namespace nao {
namespace {

using testing::ModuleHarness;

// The top camera of a standing robot, looking 15 deg down.
CameraMatrix topCamera() {
  CameraMatrix m;
  m.intrinsics = CameraIntrinsics::nominal(CameraId::Top);
  m.pose.linear() = Eigen::AngleAxisd(15 * M_PI / 180, Eigen::Vector3d::UnitY()).toRotationMatrix();
  m.pose.translation() = Eigen::Vector3d(0.05, 0, 0.5);
  return m;
}

struct Tracker {
  ModuleHarness h{"BallTracker"};
  RobotPose pose;
  GameState game;
  double time = 1;

  Tracker() {
    pose.valid = true;
    pose.covariance = Eigen::Vector3d(1e-4, 1e-4, 1e-4).asDiagonal();
    game.fromGameController = true;
    game.state = gc::State::Playing;
  }
  // One image: a ball percept at `field` (field frame) or none.
  const std::vector<BallTracks::Track>& see(const std::optional<Eigen::Vector2d>& field) {
    CameraPercepts p;
    p.processed = true;
    p.timestamp = time += 1.0 / 30;
    p.cameraMatrix = topCamera();
    if (field) {
      p.ball.seen = true;
      p.ball.position = pose.pose.inverse() * *field;
    }
    h.fix(p).fix(pose).fix(game).run();
    return h.get<BallTracks>().tracks;
  }
};

TEST(BallTracker, SetPutsTheFourBallsOnTheGoalFreeKickPositions) {
  Tracker t;
  t.game.state = gc::State::Set;
  const auto& tracks = t.see(std::nullopt);
  ASSERT_EQ(tracks.size(), 4u);
  const FieldDimensions f;
  for (const auto& track : tracks) {
    EXPECT_NEAR(std::abs(track.position.x()), f.length / 2 - f.goalBoxAreaLength, 1e-9);
    EXPECT_NEAR(std::abs(track.position.y()), f.goalBoxAreaWidth / 2, 1e-9);
    EXPECT_EQ(track.sightings, 0);  // expected, not yet seen
  }
}

TEST(BallTracker, PerceptsJoinTheNearestTrackOrStartOne) {
  Tracker t;
  t.pose.pose = Pose2(-2, 0, 0);
  t.see(Eigen::Vector2d(-1.0, 0.2));
  t.see(Eigen::Vector2d(-1.02, 0.22));
  auto tracks = t.see(Eigen::Vector2d(-1.0, 0.2));
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_EQ(tracks[0].sightings, 3);
  EXPECT_LT((tracks[0].position - Eigen::Vector2d(-1.0, 0.2)).norm(), 0.02);
  // A second ball 1.5 m away: a second track; the first keeps its place.
  tracks = t.see(Eigen::Vector2d(-0.5, 1.6));
  ASSERT_EQ(tracks.size(), 2u);
  EXPECT_LT((tracks[0].position - Eigen::Vector2d(-1.0, 0.2)).norm(), 0.02);
  // A ball off the field (the referee's spares) starts none.
  t.pose.pose = Pose2(-2, 2.5, M_PI / 2);
  tracks = t.see(Eigen::Vector2d(-2.0, 3.6));
  EXPECT_EQ(tracks.size(), 2u);
}

TEST(BallTracker, ATrackInViewThatIsNotSeenGoesButNotWhileAnotherBallIsReported) {
  Tracker t;
  t.pose.pose = Pose2(-2, 0, 0);
  t.see(Eigen::Vector2d(-0.5, 0.0));  // 1.5 m ahead: in the top camera's view
  t.see(Eigen::Vector2d(-1.0, 0.1));  // a nearer one
  // The vision reports one ball per image: while it reports the nearer, the other stays.
  for (int k = 0; k < 20; ++k) t.see(Eigen::Vector2d(-1.0, 0.1));
  ASSERT_EQ(t.h.get<BallTracks>().tracks.size(), 2u);
  // No ball in the image at all: both should have been seen; after six such images they go.
  for (int k = 0; k < 5; ++k) t.see(std::nullopt);
  EXPECT_EQ(t.h.get<BallTracks>().tracks.size(), 2u);
  EXPECT_EQ(t.see(std::nullopt).size(), 0u);
  // One behind the robot is not expected in the image: it stays.
  t.see(Eigen::Vector2d(-1.0, 0.0));
  t.pose.pose = Pose2(-2, 0, M_PI);
  for (int k = 0; k < 10; ++k) t.see(std::nullopt);
  EXPECT_EQ(t.h.get<BallTracks>().tracks.size(), 1u);
}

// A ball kicked away leaves its track where it was last taken; the vision now reports that ball
// far off, and the near track it should have shown goes.
TEST(BallTracker, ATrackLeftBehindByARollingBallGoes) {
  Tracker t;
  t.pose.pose = Pose2(-2, 0, 0);
  t.see(Eigen::Vector2d(-1.0, 0.0));
  for (int k = 0; k < 5; ++k) t.see(Eigen::Vector2d(1.5, 0.3));  // 3.5 m off: a second track
  EXPECT_EQ(t.h.get<BallTracks>().tracks.size(), 2u);
  const auto& tracks = t.see(Eigen::Vector2d(1.5, 0.3));
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_LT((tracks[0].position - Eigen::Vector2d(1.5, 0.3)).norm(), 0.01);
}

TEST(BallTracker, AfterAPointOfOursTheBallIsExpectedAtTheFarthestOwnStartPoint) {
  Tracker t;
  t.pose.pose = Pose2(-1, 1, 0);
  t.see(std::nullopt);
  t.game.ownScore = 1;
  const auto& tracks = t.see(std::nullopt);
  ASSERT_EQ(tracks.size(), 1u);
  const FieldDimensions f;
  EXPECT_NEAR(tracks[0].position.x(), -(f.length / 2 - f.goalBoxAreaLength), 1e-9);
  EXPECT_NEAR(tracks[0].position.y(), -f.goalBoxAreaWidth / 2, 1e-9);  // the far one from y = 1
}

}  // namespace
}  // namespace nao
