// The 1vs1 ball rules (scenarios/BallRules.h) on scripted ball paths: every call the rules
// make where they must, and none in legal situations (a slow ball still rolling, a ball on the
// halfway line, a ball stopped on the side line).
#include <gtest/gtest.h>

#include <cmath>

#include "scenarios/BallRules.h"

namespace {

using nao::sim::BallRules;
using Calls = std::vector<BallRules::Call>;

constexpr double kStep = 0.012;

// A ball rolling from `from` with `speed` (m/s) in `direction` under constant deceleration
// (0.5 m/s^2) until it stops; optional touches by team at given times. Returns every call.
struct Roll {
  Eigen::Vector2d from;
  Eigen::Vector2d direction;
  double speed;
  int kicker = 0;  // who touches it at t = 0
  double interceptAt = -1;  // the other team touches it then
  double seconds = 20;
};

Calls play(BallRules& rules, const Roll& r, std::vector<Eigen::Vector2d> robots = {{-3, 0}, {3, 0}}) {
  Calls all;
  const double decel = 0.5;
  const Eigen::Vector2d dir = r.direction.normalized();
  for (double t = 0; t <= r.seconds; t += kStep) {
    const double v = std::max(0.0, r.speed - decel * t);
    const double tt = std::min(t, r.speed / decel);
    const double d = r.speed * tt - 0.5 * decel * tt * tt;
    BallRules::Ball b;
    b.position = r.from + d * dir;
    b.velocity = v * dir;
    std::vector<BallRules::Touch> touches;
    if (t == 0) touches.push_back({0, r.kicker});
    if (r.interceptAt >= 0 && std::abs(t - r.interceptAt) < kStep / 2) touches.push_back({0, 1 - r.kicker});
    for (const auto& c : rules.update(t, {b}, touches, robots)) all.push_back(c);
  }
  return all;
}

nao::FieldDimensions field() { return nao::FieldDimensions{}; }

TEST(BallRules, ABallKickedFromTheOwnHalfThatStopsInTheOtherIsAPoint) {
  BallRules rules(field());
  // From (-1, 0) at 2 m/s: stops 4 m later at (3, 0).
  const Calls c = play(rules, {{-1, 0}, {1, 0}, 2.0});
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].kind, "point");
  EXPECT_EQ(c[0].how, "ball_in_half");
  EXPECT_EQ(c[0].team, 0);
  EXPECT_NEAR(c[0].at.x(), 3.0, 0.01);
  EXPECT_NEAR(c[0].t, 4.0 + 0.5, 0.05);  // stopped at 4 s, still for 0.5 s
  // The away team's the same way round.
  BallRules away(field());
  const Calls a = play(away, {{1, 0.5}, {-1, 0}, 2.0, 1});
  ASSERT_EQ(a.size(), 1u);
  EXPECT_EQ(a[0].team, 1);
}

TEST(BallRules, TheDefendersTouchAfterTheHalfwayLineCancelsThePoint) {
  BallRules rules(field());
  const Calls c = play(rules, {{-1, 0}, {1, 0}, 2.0, 0, 2.5});  // at 2.5 s the ball is at x = 2.44
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].kind, "no_point");
  EXPECT_EQ(c[0].how, "intercepted");
  EXPECT_EQ(c[0].team, 0);
  // The defender who intercepts and plays it back into the other half scores.
  BallRules back(field());
  Calls all;
  BallRules::Ball b;
  b.position = {-1, 0};
  b.velocity = {1, 0};
  double t = 0;
  for (; b.position.x() < 1.5; t += kStep, b.position.x() += kStep)
    for (const auto& call : back.update(t, {b}, t == 0 ? std::vector<BallRules::Touch>{{0, 0}} : std::vector<BallRules::Touch>{}, {}))
      all.push_back(call);
  b.velocity = {-1, 0};
  for (bool first = true; b.position.x() > -1.5; t += kStep, b.position.x() -= kStep, first = false)
    for (const auto& call : back.update(t, {b}, first ? std::vector<BallRules::Touch>{{0, 1}} : std::vector<BallRules::Touch>{}, {}))
      all.push_back(call);
  b.velocity = {0, 0};
  for (int k = 0; k < 100; ++k, t += kStep)
    for (const auto& call : back.update(t, {b}, {}, {})) all.push_back(call);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].kind, "point");
  EXPECT_EQ(all[0].team, 1);
}

TEST(BallRules, NoCallWhileTheBallRollsOrWhenItStopsOnTheHalfwayLineOrInTheOwnHalf) {
  BallRules rolling(field());
  // 1 m/s from (-1, 0): stops at x = 0 (on the halfway line) after 2 s; judged only 10 s.
  EXPECT_TRUE(play(rolling, {{-1, 0}, {1, 0}, 1.0}).empty());
  BallRules slow(field());
  Roll r{{-1, 1}, {1, 0}, 2.0};
  r.seconds = 3.9;  // still rolling (slowly) at x = 2.96
  EXPECT_TRUE(play(slow, r).empty());
  BallRules own(field());
  EXPECT_TRUE(play(own, {{-3, 0}, {1, 0}, 1.4}).empty());  // stops at x = -1.04
  // The ball kicked from the opponent half (a robot that crossed): no point for it.
  BallRules crossed(field());
  EXPECT_TRUE(play(crossed, {{0.5, 0}, {1, 0}, 1.0}).empty());
}

TEST(BallRules, ABallStoppedOnTheSideLineIsInTheField) {
  BallRules rules(field());
  // From (-1, 0) towards (2, 3): stops exactly on the side line (y = 3).
  const Eigen::Vector2d dir = Eigen::Vector2d(3, 3).normalized();
  const double dist = std::sqrt(18.0), speed = std::sqrt(2 * 0.5 * dist);
  const Calls c = play(rules, {{-1, 0}, dir, speed});
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].kind, "point");
  EXPECT_NEAR(c[0].at.y(), 3.0, 0.01);
}

TEST(BallRules, AGoalScoresForTheAttackerAndTheBallGoesBackToTheScorer) {
  BallRules rules(field());
  // Home robot at (-1, 1): the start point in its half farthest from it is (-3.9, -1.1).
  const Calls c = play(rules, {{-1, 0.2}, {1, 0}, 3.5}, {{-1, 1}, {3, 0}});
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].kind, "point");
  EXPECT_EQ(c[0].how, "goal");
  EXPECT_EQ(c[0].team, 0);
  ASSERT_TRUE(c[0].replaceAt);
  EXPECT_NEAR(c[0].replaceAt->x(), -3.9, 1e-9);
  EXPECT_NEAR(c[0].replaceAt->y(), -1.1, 1e-9);
  // An own goal counts for the other side.
  BallRules own(field());
  const Calls o = play(own, {{2, 0.1}, {1, 0}, 3.0, 1});
  ASSERT_EQ(o.size(), 1u);
  EXPECT_EQ(o[0].how, "goal");
  EXPECT_EQ(o[0].team, 0);
  // After the switch at half time the home team attacks -x.
  BallRules second(field());
  second.setHomeDefendsNegativeX(false);
  const Calls s = play(second, {{1, 0.2}, {-1, 0}, 3.5});
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].how, "goal");
  EXPECT_EQ(s[0].team, 0);
  EXPECT_GT(s[0].replaceAt->x(), 0);
}

TEST(BallRules, BallsOutGoBackWhereTheRulesSay) {
  BallRules side(field());
  // Towards the right side line at 45 deg from (1, -1): leaves it near x = 3.1.
  const Calls c = play(side, {{1, -1}, Eigen::Vector2d(1, -1), 3.0});
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].kind, "ball_out_side");
  ASSERT_TRUE(c[0].replaceAt);
  EXPECT_NEAR(c[0].replaceAt->y(), -3.0, 1e-9);
  EXPECT_NEAR(c[0].replaceAt->x(), c[0].at.x(), 1e-9);
  EXPECT_LT(c[0].at.y(), -3.075);
  EXPECT_GT(c[0].at.y(), -3.1);  // called in the cycle it left
  // Over the end line beside the goal: the goal box corner on that side.
  BallRules end(field());
  const Calls e = play(end, {{-1, 1.5}, {1, 0}, 3.5});
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].kind, "ball_out_end");
  EXPECT_NEAR(e[0].replaceAt->x(), 3.9, 1e-9);
  EXPECT_NEAR(e[0].replaceAt->y(), 1.1, 1e-9);
  // Out of play until the match replaces it; then it is judged again.
  BallRules::Ball outside;
  outside.position = {5.5, 1.5};
  EXPECT_TRUE(end.update(30, {outside}, {}, {}).empty());
  end.replaced(0);
  EXPECT_EQ(end.update(30.1, {outside}, {}, {}).size(), 1u);
}

}  // namespace
