// The striker's kick choice (controllers/behavior/KickChoice.h) against the field's geometry:
// where a goal is open it kicks through the gap; a ball-in-half kick stops in the opponent
// half for every error the kick may make; otherwise the ball goes forward and stays on the field.
// The geometry of the ball-in-half kick is checked with a 3.2 m kick (the kick on the carpet
// before 2026-12-06), which needs it most; the committed 6.6 m kick's goal kicks on their own.
#include <gtest/gtest.h>

#include <cmath>

#include "controllers/behavior/KickChoice.h"

namespace {

using nao::behavior::chooseKick;
using nao::behavior::KickChoice;
using nao::behavior::KickChoiceParams;

constexpr double kDeg = M_PI / 180;

nao::FieldDimensions field() { return nao::FieldDimensions{}; }

KickChoiceParams shortKick() {
  KickChoiceParams p;
  p.travel = 3.2;
  return p;
}

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
  const KickChoice k = chooseKick({-1, 0}, std::nullopt, field(), shortKick());
  EXPECT_EQ(k.kind, KickChoice::Kind::Half);
  EXPECT_NEAR(k.direction, 0, 1e-9);
  EXPECT_NEAR(k.stop.x(), 2.2, 1e-9);
  // The long kick shoots at the open goal from there: short, it still stops in the other half.
  const KickChoice goal = chooseKick({-1, 0}, std::nullopt, field());
  EXPECT_EQ(goal.kind, KickChoice::Kind::Goal);
  EXPECT_NEAR(goal.direction, 0, 1e-9);
}

TEST(KickChoice, EveryBallInHalfKickStopsInTheOpponentHalfWhateverTheKicksError) {
  const KickChoiceParams p = shortKick();
  int half = 0, advance = 0;
  for (double x = -4.3; x <= -0.2; x += 0.3)
    for (double y = -2.9; y <= 2.9; y += 0.4) {
      const Eigen::Vector2d ball(x, y);
      const KickChoice k = chooseKick(ball, Eigen::Vector2d(2, -y), field(), p);
      ASSERT_NE(k.kind, KickChoice::Kind::Goal) << "the short kick reaches no goal from the own half";
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

// The long kick: at the goal wherever the longest travel reaches it and the shortest crosses the
// halfway line, through an open gap; otherwise as before.
TEST(KickChoice, TheLongKickShootsAtTheGoalFromWhereAShortOneStillScoresTheHalf) {
  const KickChoiceParams p;
  const Eigen::Vector2d goal(4.5, 0);
  int goals = 0;
  for (double x = -4.3; x <= -0.2; x += 0.3)
    for (double y = -2.9; y <= 2.9; y += 0.4) {
      const Eigen::Vector2d ball(x, y);
      const KickChoice k = chooseKick(ball, std::nullopt, field(), p);
      const double toGoal = (goal - ball).norm();
      if (k.kind != KickChoice::Kind::Goal) {
        EXPECT_TRUE(toGoal > p.travel * (1 + p.travelSpread) ||
                    x + p.travel * (1 - p.travelSpread) * (4.5 - x) / toGoal < 0.2)
            << "an open goal in reach not shot at from " << x << ", " << y;
        continue;
      }
      ++goals;
      const Eigen::Vector2d along(std::cos(k.direction), std::sin(k.direction));
      // The aim passes between the posts; the shortest kick stops beyond the halfway line.
      const double atLine = (4.5 - x) / along.x();
      EXPECT_LT(std::abs(y + atLine * along.y()), 0.7) << x << ", " << y;
      EXPECT_GT((ball + p.travel * (1 - p.travelSpread) * along).x(), 0.075) << x << ", " << y;
      EXPECT_GE(p.travel * (1 + p.travelSpread), atLine) << x << ", " << y;
    }
  EXPECT_GT(goals, 80);  // of 210 places in the own half
}

TEST(KickChoice, TheBallInHalfKickKeepsAwayFromTheOpponent) {
  const KickChoice k = chooseKick({-0.5, 0}, Eigen::Vector2d(2.5, 0), field(), shortKick());
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
  EXPECT_NE(chooseKick({-1.5, 0}, std::nullopt, field(), shortKick()).kind, KickChoice::Kind::Goal);  // 6 m
  EXPECT_NE(chooseKick({-4.0, 0}, std::nullopt, field()).kind, KickChoice::Kind::Goal);  // 8.5 m
}

}  // namespace
