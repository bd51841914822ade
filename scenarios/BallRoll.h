#pragma once
// The simulator's rolling ball against the ball model's constant-deceleration roll
// (perception/modeling/BallFilter.h): the ball is set rolling on the empty field at several
// speeds and directions (World::placeBall with a velocity, no robot), its true path recorded
// until it stops, and the deceleration fitted. Used by `nao-soccer train friction`.
#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "perception/FieldDimensions.h"

namespace nao::sim {

struct BallRollSpec {
  double speed = 2;      // m/s at the start, rolling (no sliding)
  double direction = 0;  // rad, field frame
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
};

// One roll as the simulator played it.
struct BallRoll {
  BallRollSpec spec;
  Eigen::Vector2d end = Eigen::Vector2d::Zero();  // where it stopped (field frame)
  double distance = 0;  // m, start to end
  double seconds = 0;   // until its speed fell under 1 cm/s
  bool stopped = false;  // false: still rolling at the time limit
  bool blocked = false;  // it touched something other than the carpet (a wall, a goal): not fitted
  double bend = 0;       // rad: the direction from start to end against the start direction
  // Decelerations (m/s^2): v0^2 / (2 distance); least squares slope of the speed over time
  // while faster than 10 % of v0; and the same slope over the first and second halves of the
  // speed (above and below v0 / 2) to show whether it is constant.
  double frictionFromDistance = 0, frictionFromSpeed = 0, frictionFast = 0, frictionSlow = 0;
  std::vector<double> t, speed;  // the true speed over time, one sample per 12 ms cycle
};

struct BallRollOptions {
  FieldDimensions field;
  int rolls = 16;           // speeds evenly spaced from minSpeed to maxSpeed
  double minSpeed = 0.5, maxSpeed = 2;  // m/s (2 m/s: a kick's roll, 6.7 m on the carpet)
  std::uint64_t seed = 1;   // jitters the directions (+-5 deg)
  double maxSeconds = 30;   // per roll
  std::function<void(int done, int total)> progress;
};

// The rolls of `options`: eight directions every 45 deg in turn (jittered by +-5 deg), each path
// through the centre spot (2 m beside it when along the field, clear of the goals), starting
// far enough back to stay clear of the hall walls.
std::vector<BallRollSpec> ballRollSpecs(const BallRollOptions& options);
// Plays one roll in a world with the field and one ball.
BallRoll rollBall(const FieldDimensions& field, const BallRollSpec& spec, double maxSeconds = 30);

// The constant deceleration that predicts the stop positions best over the rolls that stopped
// freely: least squares on the rolling distance, d_i = v_i^2 / (2 a) (minimising sum (d_i - k v_i^2 / 2)^2 over k = 1 / a).
double fitFriction(const std::vector<BallRoll>& rolls);
// Where the constant-deceleration model (BallFilter::endPosition) says the roll stops.
Eigen::Vector2d predictedEnd(const BallRollSpec& spec, double friction);

struct BallRollFit {
  double friction = 0;     // m/s^2
  double oldFriction = 0;  // the value compared against (the previous default)
  std::vector<BallRoll> rolls;
  std::vector<double> endErrors, oldEndErrors;  // m, per roll
  nlohmann::json toJson() const;
};

BallRollFit fitBallRolls(const BallRollOptions& options, double oldFriction);

}  // namespace nao::sim
