// The 1vs1 rules on robots (scenarios/RobotRules.h) on scripted robots: each rule's call where
// it must come, and no call in legal situations (a robot standing near the halfway line, one
// getting up in time, a robot that looks around now and then, a normal stance).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "scenarios/RobotRules.h"

namespace {

using nao::sim::PenaltyRule;
using nao::sim::RobotRules;
using State = nao::gc::State;

constexpr double kStep = 0.012;

// A robot standing at (x, y) facing theta with its feet `stance` m apart (soles 0.16 x 0.09 m).
RobotRules::Truth standing(double x, double y, double theta = 0, double stance = 0.1) {
  RobotRules::Truth t;
  const Eigen::Vector2d forward(std::cos(theta), std::sin(theta)), left(-std::sin(theta), std::cos(theta));
  t.torso = {x, y};
  for (int f = 0; f < 2; ++f) {
    const Eigen::Vector2d c = t.torso + (f ? -1 : 1) * stance / 2 * left;
    t.feet[static_cast<std::size_t>(f)] = c;
    int k = 0;
    for (double a : {-0.08, 0.08})
      for (double b : {-0.045, 0.045}) t.soleCorners[static_cast<std::size_t>(4 * f + k++)] = c + a * forward + b * left;
  }
  return t;
}

struct Result {
  bool called = false;
  PenaltyRule rule{};
  double t = -1;
  std::string evidence;
};

// Runs `seconds` of cycles; `truth(t)` scripts the robot. Stops at the first call.
Result run(RobotRules& rules, State state, double seconds, const std::function<RobotRules::Truth(double)>& truth,
           double t0 = 0) {
  for (double t = t0; t <= t0 + seconds; t += kStep)
    if (const auto call = rules.update(t, state, truth(t))) return {true, call->rule, t, call->evidence};
  return {};
}

nao::FieldDimensions field() { return nao::FieldDimensions{}; }

TEST(RobotRules, AStandingActiveRobotInItsHalfIsNeverCalled) {
  RobotRules rules(field(), 0);
  // Its toes 0.03 m short of the halfway line's edge.
  EXPECT_FALSE(run(rules, State::Playing, 60, [](double) { return standing(-0.135, 0.5); }).called);
  RobotRules away(field(), 1);
  EXPECT_FALSE(run(away, State::Playing, 60, [](double) { return standing(2, -2.9, M_PI); }).called);
}

TEST(RobotRules, TouchingTheHalfwayLineOrLeavingTheCarpetIsCalled) {
  RobotRules toes(field(), 0);
  const Result r = run(toes, State::Playing, 1, [](double) { return standing(-0.1, 0); });  // toes at -0.02
  ASSERT_TRUE(r.called);
  EXPECT_EQ(r.rule, PenaltyRule::HalfwayLine);
  EXPECT_NE(r.evidence.find("-0.02"), std::string::npos) << r.evidence;
  RobotRules ready(field(), 1);
  EXPECT_EQ(run(ready, State::Ready, 1, [](double) { return standing(-0.3, 0); }).rule, PenaltyRule::HalfwayLine);
  RobotRules off(field(), 0);
  // Walking out over the side: the carpet ends 0.7 m beyond the side line.
  const Result o = run(off, State::Playing, 10, [](double t) { return standing(-2, -3.3 - 0.1 * t, -M_PI / 2); });
  ASSERT_TRUE(o.called);
  EXPECT_EQ(o.rule, PenaltyRule::LeavingTheField);
  EXPECT_NEAR(-3.3 - 0.1 * o.t, -3.7 - 0.08, 0.02);  // when the last sole corner left
  // After the half time the home team's half is positive x.
  RobotRules second(field(), 0);
  second.setHomeDefendsNegativeX(false);
  EXPECT_FALSE(run(second, State::Playing, 5, [](double) { return standing(2, 0, M_PI); }).called);
  EXPECT_EQ(run(second, State::Playing, 5, [](double) { return standing(-2, 0); }).rule, PenaltyRule::HalfwayLine);
}

RobotRules::Truth lying(double x, double tilt, double height) {
  RobotRules::Truth t = standing(x, 0);
  t.tilt = tilt;
  t.height = height;
  return t;
}

TEST(RobotRules, AFallenRobotMustStartGettingUpIn5sAndStandIn20s) {
  RobotRules still(field(), 0);
  const Result a = run(still, State::Playing, 30, [](double) { return lying(-2, 90, 0.08); });
  ASSERT_TRUE(a.called);
  EXPECT_EQ(a.rule, PenaltyRule::FallenRobot);
  EXPECT_NEAR(a.t, 5, 0.02);
  EXPECT_NE(a.evidence.find("no get-up started"), std::string::npos) << a.evidence;
  // Starts at 2 s but stays half up.
  RobotRules stuck(field(), 0);
  const Result b = run(stuck, State::Playing, 30, [](double t) { return t < 2 ? lying(-2, 90, 0.08) : lying(-2, 60, 0.12); });
  ASSERT_TRUE(b.called);
  EXPECT_NEAR(b.t, 20, 0.02);
  // Up at 8 s and stays up: no call (legal).
  RobotRules up(field(), 0);
  EXPECT_FALSE(run(up, State::Playing, 40, [](double t) { return t < 2 ? lying(-2, 90, 0.08) : t < 8 ? lying(-2, 60, 0.12) : standing(-2, 0); }).called);
  // Up at 8 s, standing a little low (a randomised robot walking: torso 0.218 m, tilt 4 deg):
  // standing all the same (eval match seed 16 at 8329e0d was called here).
  RobotRules low(field(), 0);
  EXPECT_FALSE(run(low, State::Playing, 40, [](double t) { return t < 2 ? lying(-2, 90, 0.08) : t < 8 ? lying(-2, 60, 0.12) : lying(-2, 4, 0.218); }).called);
  // Kneeling upright (torso 0.18 m) is not standing: called at 20 s.
  RobotRules kneeling(field(), 0);
  EXPECT_NEAR(run(kneeling, State::Playing, 40, [](double t) { return t < 2 ? lying(-2, 90, 0.08) : lying(-2, 5, 0.18); }).t, 20, 0.02);
  // Up at 8 s, down again at 12 s (before 10 s upright): the same fall, called at 20 s.
  RobotRules again(field(), 0);
  const Result c = run(again, State::Playing, 40, [](double t) {
    return t < 2 ? lying(-2, 90, 0.08) : t < 8 ? lying(-2, 60, 0.12) : t < 12 ? standing(-2, 0) : lying(-2, 90, 0.08);
  });
  ASSERT_TRUE(c.called);
  EXPECT_NEAR(c.t, 20, 0.02);
  // Not judged before the game runs.
  RobotRules initial(field(), 0);
  EXPECT_FALSE(run(initial, State::Initial, 30, [](double) { return lying(-2, 90, 0.08); }).called);
}

TEST(RobotRules, TenSecondsWithoutActivityIsInactive) {
  RobotRules idle(field(), 0);
  const Result r = run(idle, State::Playing, 30, [](double) {
    auto t = standing(-2, 0);
    t.active = false;
    return t;
  });
  ASSERT_TRUE(r.called);
  EXPECT_EQ(r.rule, PenaltyRule::InactiveRobot);
  EXPECT_NEAR(r.t, 10, 0.02);
  RobotRules looking(field(), 0);  // looks around for 1 s every 8 s: legal
  EXPECT_FALSE(run(looking, State::Playing, 60, [](double s) {
                 auto t = standing(-2, 0);
                 t.active = std::fmod(s, 8.0) < 1.0;
                 return t;
               }).called);
}

// Idle before a global game stuck, then READY and SET standing still: PLAYING starts a new count
// (a call at the first cycle of PLAYING was seen in a whole game at 8cc3a74).
TEST(RobotRules, InactivityBeforeAStoppageDoesNotCarryIntoTheNextPlaying) {
  RobotRules rules(field(), 0);
  const auto idle = [](double) {
    auto t = standing(-2, 0);
    t.active = false;
    return t;
  };
  EXPECT_FALSE(run(rules, State::Playing, 8, idle).called);
  EXPECT_FALSE(run(rules, State::Ready, 45, idle, 8).called);
  EXPECT_FALSE(run(rules, State::Set, 5, idle, 53).called);
  const Result r = run(rules, State::Playing, 20, idle, 58.01);
  ASSERT_TRUE(r.called);
  EXPECT_EQ(r.rule, PenaltyRule::InactiveRobot);
  EXPECT_NEAR(r.t, 68.01, 0.02);
}

TEST(RobotRules, AWideStanceAHandOnTheBallAndTheGoalAreCalled) {
  RobotRules wide(field(), 0);
  const Result w = run(wide, State::Playing, 10, [](double) { return standing(-2, 0, 0, 0.4); });
  ASSERT_TRUE(w.called);
  EXPECT_EQ(w.rule, PenaltyRule::PlayerStance);
  EXPECT_NEAR(w.t, 5, 0.02);
  RobotRules normal(field(), 0);
  EXPECT_FALSE(run(normal, State::Playing, 10, [](double) { return standing(-2, 0, 0, 0.25); }).called);
  RobotRules hand(field(), 0);
  const Result h = run(hand, State::Playing, 1, [](double s) {
    auto t = standing(-2, 0);
    t.handOnBall = s > 0.5;
    return t;
  });
  ASSERT_TRUE(h.called);
  EXPECT_EQ(h.rule, PenaltyRule::PlayingWithArms);
  RobotRules falling(field(), 0);  // a hand on the ball while falling: not the arms rule
  const Result f = run(falling, State::Playing, 3, [](double) {
    auto t = lying(-2, 90, 0.08);
    t.handOnBall = true;
    return t;
  });
  EXPECT_FALSE(f.called);
  RobotRules goal(field(), 0);
  const Result g = run(goal, State::Playing, 10, [](double) { return standing(-4.75, 0.2); });
  ASSERT_TRUE(g.called);
  EXPECT_EQ(g.rule, PenaltyRule::GoalArea);
  EXPECT_NEAR(g.t, 5, 0.02);
}

TEST(RobotRules, InSetTheRobotMustBeInItsHalfAndKeepItsFeetStill) {
  RobotRules cross(field(), 0);
  const Result c = run(cross, State::Set, 1, [](double) { return standing(0.2, 0); });
  ASSERT_TRUE(c.called);
  EXPECT_EQ(c.rule, PenaltyRule::IllegalPositionInSet);
  EXPECT_NEAR(c.t, 0, 1e-9);
  RobotRules inGoal(field(), 0);
  EXPECT_EQ(run(inGoal, State::Set, 1, [](double) { return standing(-4.7, 0); }).rule, PenaltyRule::IllegalPositionInSet);
  RobotRules walking(field(), 1);
  const Result m = run(walking, State::Set, 3, [](double t) { return standing(1.5 + 0.1 * t, 0, M_PI); });
  ASSERT_TRUE(m.called);
  EXPECT_EQ(m.rule, PenaltyRule::MotionInSet);
  EXPECT_NEAR(m.t, 1.5, 0.02) << "still walking 1 s into SET, then 0.05 m more";
  RobotRules settled(field(), 1);  // swaying 2 cm: legal
  EXPECT_FALSE(run(settled, State::Set, 5, [](double t) { return standing(1.5 + 0.02 * std::sin(t), 0, M_PI); }).called);
  // Walking when SET begins, stopping within the step it hears SET in (0.1 m in 0.6 s): legal.
  RobotRules stopping(field(), 1);
  EXPECT_FALSE(run(stopping, State::Set, 5, [](double t) { return standing(1.5 + 0.1 * std::min(t / 0.6, 1.0), 0, M_PI); }).called);
}

}  // namespace
