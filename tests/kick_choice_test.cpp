// The striker's kick choice (controllers/behavior/KickChoice.h) against the field's geometry:
// where a goal is open it kicks through the gap; a ball-in-half kick stops in the opponent
// half for every error the kick may make; otherwise the ball goes forward and stays on the field.
#include <gtest/gtest.h>

#include <cmath>

#include "controllers/behavior/KickChoice.h"

namespace {

using nao::behavior::chooseKick;
using nao::behavior::KickChoice;
using nao::behavior::KickChoiceParams;

constexpr double kDeg = M_PI / 180;

nao::FieldDimensions field() { return nao::FieldDimensions{}; }

// Every stop of the kick in `direction` (+-inaccuracy, travel +-spread), checked by `ok`.
template <class F>
bool everyStop(const Eigen::Vector2d& ball, double direction, const KickChoiceParams& p, F ok) {
  for (double e = -p.inaccuracy; e <= p.inaccuracy + 1e-9; e += 2.5)
    for (double t = p.travel * (1 - p.travelSpread); t <= p.travel * (1 + p.travelSpread) + 1e-9; t += 0.1) {
      const double a = direction + e * kDeg;
      if (!ok(ball + t * Eigen::Vector2d(std::cos(a), std::sin(a)))) return false;
    }
  return true;
}

TEST(KickChoice, FromTheMiddleOfTheOwnHalfTheBallGoesStraightIntoTheOtherHalf) {
  const KickChoice k = chooseKick({-1, 0}, std::nullopt, field());
  EXPECT_EQ(k.kind, KickChoice::Kind::Half);
  EXPECT_NEAR(k.direction, 0, 1e-9);
  EXPECT_NEAR(k.stop.x(), 2.2, 1e-9);
}

TEST(KickChoice, EveryBallInHalfKickStopsInTheOpponentHalfWhateverTheKicksError) {
  const KickChoiceParams p;
  int half = 0, advance = 0;
  for (double x = -4.3; x <= -0.2; x += 0.3)
    for (double y = -2.9; y <= 2.9; y += 0.4) {
      const Eigen::Vector2d ball(x, y);
      const KickChoice k = chooseKick(ball, Eigen::Vector2d(2, -y), field(), p);
      if (k.kind == KickChoice::Kind::Half) {
        ++half;
        // In the opponent half (beyond the halfway line's edge, ball radius included) and on the
        // field, or in the goal.
        EXPECT_TRUE(everyStop(ball, k.direction, p, [](const Eigen::Vector2d& s) {
          const bool goal = s.x() > 4.5 && std::abs(s.y()) < 0.7;
          return s.x() > 0.025 + 0.05 && std::abs(s.y()) < 3.0 && (s.x() < 4.5 || goal);
        })) << "ball " << x << ", " << y << " direction " << k.direction / kDeg;
      } else {
        ++advance;
        EXPECT_EQ(k.kind, KickChoice::Kind::Advance);
        EXPECT_LT(x, -0.9) << "a ball this near the halfway line can always be kicked over it: " << x << ", " << y;
        // Forward, and not out over a side line for the nominal travel.
        EXPECT_LT(std::abs(k.direction), 90 * kDeg);
        EXPECT_LT(std::abs(k.stop.y()), 3.0) << x << ", " << y;
      }
    }
  EXPECT_GT(half, 50);
  EXPECT_GT(advance, 10);  // from the goal box corners the kick does not reach the halfway line
}

TEST(KickChoice, TheBallInHalfKickKeepsAwayFromTheOpponent) {
  const KickChoice k = chooseKick({-0.5, 0}, Eigen::Vector2d(2.5, 0), field());
  ASSERT_EQ(k.kind, KickChoice::Kind::Half);
  EXPECT_GT((k.stop - Eigen::Vector2d(2.5, 0)).norm(), 1.0);
  EXPECT_GT(std::abs(k.direction), 10 * kDeg);
}

TEST(KickChoice, AnOpenGoalWithinReachIsShotThroughItsWidestGap) {
  const KickChoice open = chooseKick({2.5, 0}, std::nullopt, field());
  ASSERT_EQ(open.kind, KickChoice::Kind::Goal);
  EXPECT_NEAR(open.direction, 0, 1e-9);
  EXPECT_NEAR(open.openAngle, 2 * std::atan(0.7 / 2.0) / kDeg, 1e-6);
  // A keeper 1 m ahead in the middle leaves two gaps of about 7.8 deg; the left one is taken
  // when the keeper stands a little to the right.
  const KickChoice gap = chooseKick({2.5, 0}, Eigen::Vector2d(3.5, -0.05), field());
  ASSERT_EQ(gap.kind, KickChoice::Kind::Goal);
  EXPECT_GT(gap.direction, 10 * kDeg);
  EXPECT_LT(gap.direction, 20 * kDeg);
  EXPECT_GE(gap.openAngle, 6);
  // A keeper close in front closes it; out of reach is no goal kick either.
  EXPECT_NE(chooseKick({2.5, 0}, Eigen::Vector2d(3.0, 0), field()).kind, KickChoice::Kind::Goal);
  EXPECT_NE(chooseKick({1.0, 0}, std::nullopt, field()).kind, KickChoice::Kind::Goal);
}

}  // namespace
