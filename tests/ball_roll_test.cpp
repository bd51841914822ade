// The ball model's constant deceleration against the simulator's rolling ball
// (scenarios/BallRoll.h, `nao-soccer train friction`). The simulator's stop position is the
// truth. Along one direction the deceleration is constant: a fit on three rolls predicts where a
// held-out roll stops within centimetres; and it is the same in every direction (the carpet's
// rolling resistance in sim/World.cpp; MuJoCo's rolling friction under its pyramidal cone was
// 1.4 times stronger along the field's axes than along its diagonals). The committed friction
// (config/parameters/BallLocator.json, the code default) is the fit over all directions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "controllers/modules/BallLocator.h"
#include "scenarios/BallRoll.h"

namespace {

using nao::sim::BallRoll;
using nao::sim::BallRollSpec;

BallRollSpec spec(double speed, double directionDeg, const Eigen::Vector2d& start) {
  BallRollSpec s;
  s.speed = speed;
  s.direction = directionDeg * M_PI / 180;
  s.start = start;
  return s;
}

// Rolls of 0.6, 1.2 and 1.8 m/s fitted (0.6-5.4 m on the carpet), one of 1.5 m/s held out; all
// from `start` along `directionDeg`.
double fitAndPredict(double directionDeg, const Eigen::Vector2d& start) {
  const nao::FieldDimensions field;
  std::vector<BallRoll> rolls;
  for (double speed : {0.6, 1.2, 1.8}) rolls.push_back(nao::sim::rollBall(field, spec(speed, directionDeg, start)));
  for (const BallRoll& r : rolls) {
    EXPECT_TRUE(r.stopped && !r.blocked) << r.spec.speed;
    EXPECT_GT(r.distance, 0.5) << r.spec.speed;
  }
  const double friction = nao::sim::fitFriction(rolls);
  // Each roll's own deceleration (from its distance) lies near the fit: one constant serves.
  for (const BallRoll& r : rolls) EXPECT_NEAR(r.frictionFromDistance, friction, 0.05 * friction) << r.spec.speed;
  const BallRoll heldOut = nao::sim::rollBall(field, spec(1.5, directionDeg, start));
  EXPECT_TRUE(heldOut.stopped && !heldOut.blocked);
  const double error = (nao::sim::predictedEnd(heldOut.spec, friction) - heldOut.end).norm();
  std::printf("direction %.0f deg: friction %.4f m/s^2; held-out roll of %.2f m stops %.3f m from the prediction\n",
              directionDeg, friction, heldOut.distance, error);
  EXPECT_LT(error, 0.05) << directionDeg;
  // Control: twice the friction misses by metres.
  EXPECT_GT((nao::sim::predictedEnd(heldOut.spec, 2 * friction) - heldOut.end).norm(), 1.5);
  return friction;
}

TEST(BallRoll, ConstantDecelerationAlongADirectionPredictsAHeldOutStop) {
  const double alongAxis = fitAndPredict(0, Eigen::Vector2d(-6, 2));  // beside the goals
  const double diagonal = fitAndPredict(45, Eigen::Vector2d(-4, -4));
  // The same along the axes and the diagonals: one constant serves every direction.
  EXPECT_NEAR(alongAxis / diagonal, 1.0, 0.02);
}

TEST(BallRoll, CommittedFrictionIsTheFitOverAllDirections) {
  nao::sim::BallRollOptions o;  // 16 rolls, 0.5-2 m/s, eight directions
  const nao::sim::BallRollFit fit = nao::sim::fitBallRolls(o, 0.8);  // the carpet's old value
  ASSERT_EQ(fit.rolls.size(), 16u);
  for (const BallRoll& r : fit.rolls) EXPECT_TRUE(r.stopped && !r.blocked) << r.spec.speed;
  const double committed = nao::modules::BallLocator::Params{}.filter.friction;
  EXPECT_NEAR(committed, fit.friction, 0.03 * fit.friction);
  std::vector<double> e = fit.endErrors, old = fit.oldEndErrors;
  std::sort(e.begin(), e.end());
  std::sort(old.begin(), old.end());
  std::printf("all directions: friction %.4f m/s^2, stop error median %.3f m (0.8 m/s^2: %.3f m)\n", fit.friction,
              e[e.size() / 2], old[old.size() / 2]);
  EXPECT_LT(e[e.size() / 2] * 5, old[old.size() / 2]);
}

TEST(BallRoll, SpecsAreDeterministic) {
  nao::sim::BallRollOptions o;
  o.rolls = 8;
  const auto a = nao::sim::ballRollSpecs(o), b = nao::sim::ballRollSpecs(o);
  ASSERT_EQ(a.size(), 8u);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].direction, b[i].direction);
    EXPECT_EQ(a[i].start, b[i].start);
  }
  EXPECT_DOUBLE_EQ(a.front().speed, 0.5);
  EXPECT_DOUBLE_EQ(a.back().speed, 2.0);
}

}  // namespace
