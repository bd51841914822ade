// The kick in the simulator (ground truth): the robot walks to the ball, kicks it in the
// requested direction and stays on its feet. NAO_TEST_QUICK shortens the run to one kick.
#include <cmath>
#include <cstdlib>

#include <gtest/gtest.h>

#include "controllers/Kick.h"
#include "scenarios/KickEval.h"

namespace nao {
namespace {

constexpr double kDeg = M_PI / 180;

TEST(Kick, BallTargetIsInFrontOfTheKickingFoot) {
  const Kick::Params p;
  const Eigen::Vector2d l = Kick::ballTarget(true, p), r = Kick::ballTarget(false, p);
  EXPECT_GT(l.x(), 0.15);
  EXPECT_GT(l.y(), 0);
  EXPECT_LT(r.y(), 0);
  EXPECT_DOUBLE_EQ(l.x(), r.x());
  EXPECT_GT(Kick(p).duration(), 1.0);
}

TEST(Kick, WalksToTheBallAndKicksItTheRequestedWay) {
  struct Case {
    double distance, bearing, direction;
  };
  std::vector<Case> cases = {{0.5, 0, 0}, {0.6, 30 * kDeg, -30 * kDeg}};
  if (std::getenv("NAO_TEST_QUICK")) cases.resize(1);
  for (const Case& c : cases) {
    sim::KickTrialOptions o;
    o.ballDistance = c.distance;
    o.ballBearing = c.bearing;
    o.direction = c.direction;
    const sim::KickTrialResult r = sim::runKick(o);
    std::printf("kick: done %d after %.1f s, ball %.2f m at %.1f m/s, direction error %.1f deg, %d falls\n", r.kicked,
                r.time, r.travel, r.ballSpeed, r.directionError / kDeg, r.falls);
    EXPECT_TRUE(r.kicked);
    EXPECT_EQ(r.falls, 0);
    EXPECT_LT(r.time, 20.0);     // walked up without pushing the ball away first
    EXPECT_GT(r.travel, 2.5);
    EXPECT_LT(r.directionError, 10 * kDeg);
  }
}

}  // namespace
}  // namespace nao
