#include "scenarios/BallRoll.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "perception/modeling/BallFilter.h"
#include "robot/math/Pose2.h"
#include "robot/Error.h"
#include "sim/World.h"

namespace nao::sim {

namespace {

constexpr double kStopSpeed = 0.01;  // m/s: the ball counts as stopped below this

// The least squares slope of y over x (0 with fewer than 3 points).
double slope(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  if (n < 3) return 0;
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) mx += x[i], my += y[i];
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < n; ++i) sxy += (x[i] - mx) * (y[i] - my), sxx += (x[i] - mx) * (x[i] - mx);
  return sxx > 0 ? sxy / sxx : 0;
}

// -slope of the speed over time while the speed lies in (lo, hi].
double decelerationBetween(const BallRoll& r, double lo, double hi) {
  std::vector<double> t, v;
  for (std::size_t i = 0; i < r.t.size(); ++i)
    if (r.speed[i] > lo && r.speed[i] <= hi) t.push_back(r.t[i]), v.push_back(r.speed[i]);
  return -slope(t, v);
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

nlohmann::json vec2(const Eigen::Vector2d& p) { return {std::round(p.x() * 1e4) / 1e4, std::round(p.y() * 1e4) / 1e4}; }

}  // namespace

std::vector<BallRollSpec> ballRollSpecs(const BallRollOptions& o) {
  std::vector<BallRollSpec> specs;
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> jitter(-5 * M_PI / 180, 5 * M_PI / 180);
  // The carpet plane reaches the hall walls, 3 m beyond the border strip (sim/SceneBuilder.cpp);
  // a roll that touches anything but the carpet is marked blocked all the same.
  const double wallX = o.field.length / 2 + o.field.borderStripWidth + 3 - 0.5;
  const double wallY = o.field.width / 2 + o.field.borderStripWidth + 3 - 0.5;
  for (int i = 0; i < o.rolls; ++i) {
    BallRollSpec s;
    s.speed = o.rolls == 1 ? o.maxSpeed : o.minSpeed + (o.maxSpeed - o.minSpeed) * i / (o.rolls - 1);
    // Eight directions in turn (every 45 deg, a different order per lap), each jittered: the
    // simulator's rolling resistance depends on the direction (docs/modeling.md).
    static constexpr int kOrder[8] = {0, 2, 5, 7, 1, 3, 4, 6};
    s.direction = Pose2::wrap(kOrder[i % 8] * M_PI / 4 + jitter(rng));
    const Eigen::Vector2d dir(std::cos(s.direction), std::sin(s.direction));
    // Through the centre spot, or 2 m beside it when running along the field (the goals).
    const bool alongX = std::abs(dir.x()) > std::cos(25 * M_PI / 180);
    const Eigen::Vector2d through(0, alongX ? (i % 2 ? -2.0 : 2.0) : 0.0);
    // Back from there towards the wall behind, as far as half the path at 0.25 m/s^2 asks (a
    // guess on the slow side of carpets: the roll stays clear of the far wall).
    double back = 1e9;
    if (std::abs(dir.x()) > 1e-9) back = std::min(back, (wallX + std::copysign(through.x(), dir.x())) / std::abs(dir.x()));
    if (std::abs(dir.y()) > 1e-9) back = std::min(back, (wallY + std::copysign(through.y(), dir.y())) / std::abs(dir.y()));
    s.start = through - std::min(back, s.speed * s.speed / (2 * 0.25) / 2) * dir;
    specs.push_back(s);
  }
  return specs;
}

BallRoll rollBall(const FieldDimensions& field, const BallRollSpec& spec, double maxSeconds) {
  SceneSpec scene;
  scene.field = field;
  scene.robots.clear();
  scene.balls = {Eigen::Vector3d(spec.start.x(), spec.start.y(), 0.05)};
  World world(scene);
  const Eigen::Vector3d v0(spec.speed * std::cos(spec.direction), spec.speed * std::sin(spec.direction), 0);
  world.placeBall(0, Eigen::Vector3d(spec.start.x(), spec.start.y(), 0.05), v0);
  const mjModel* m = world.model();
  const mjData* d = world.data();
  const int carpet = mj_name2id(m, mjOBJ_GEOM, "field/carpet");
  const int ballBody = mj_name2id(m, mjOBJ_BODY, "ball0");
  if (carpet < 0 || ballBody < 0) throw Error("train friction", "the scene has no field/carpet geom or ball0 body");
  BallRoll r;
  r.spec = spec;
  const double t0 = world.time();
  r.t.push_back(0);
  r.speed.push_back(spec.speed);
  int slow = 0;
  while (world.time() - t0 < maxSeconds) {
    world.stepCycle();
    for (int c = 0; c < d->ncon; ++c) {
      const int g1 = d->contact[c].geom1, g2 = d->contact[c].geom2;
      const bool ball1 = m->geom_bodyid[g1] == ballBody, ball2 = m->geom_bodyid[g2] == ballBody;
      if ((ball1 && g2 != carpet) || (ball2 && g1 != carpet)) r.blocked = true;
    }
    const double speed = world.ballVelocity(0).head<2>().norm();
    r.t.push_back(world.time() - t0);
    r.speed.push_back(speed);
    if (speed < kStopSpeed) {
      if (++slow >= 5) {  // 60 ms still: stopped
        r.stopped = true;
        break;
      }
    } else {
      slow = 0;
      r.seconds = world.time() - t0;
    }
  }
  r.end = world.ballPosition(0).head<2>();
  r.distance = (r.end - spec.start).norm();
  if (r.distance > 1e-6) {
    const Eigen::Vector2d path = (r.end - spec.start) / r.distance;
    r.bend = std::atan2(std::cos(spec.direction) * path.y() - std::sin(spec.direction) * path.x(),
                        std::cos(spec.direction) * path.x() + std::sin(spec.direction) * path.y());
  }
  r.frictionFromDistance = r.distance > 0 ? spec.speed * spec.speed / (2 * r.distance) : 0;
  r.frictionFromSpeed = decelerationBetween(r, 0.1 * spec.speed, 2 * spec.speed);
  r.frictionFast = decelerationBetween(r, 0.5 * spec.speed, 2 * spec.speed);
  r.frictionSlow = decelerationBetween(r, 0.1 * spec.speed, 0.5 * spec.speed);
  return r;
}

double fitFriction(const std::vector<BallRoll>& rolls) {
  double num = 0, den = 0;  // d = k q with q = v^2 / 2: k = sum(d q) / sum(q^2)
  for (const BallRoll& r : rolls) {
    if (r.blocked || !r.stopped) continue;
    const double q = r.spec.speed * r.spec.speed / 2;
    num += r.distance * q;
    den += q * q;
  }
  if (!(num > 0) || !(den > 0)) throw Error("train friction", "no roll stopped freely on the carpet after covering any distance");
  return den / num;
}

Eigen::Vector2d predictedEnd(const BallRollSpec& spec, double friction) {
  const Eigen::Vector2d v(spec.speed * std::cos(spec.direction), spec.speed * std::sin(spec.direction));
  return BallFilter::endPosition(spec.start, v, friction);
}

BallRollFit fitBallRolls(const BallRollOptions& options, double oldFriction) {
  BallRollFit fit;
  fit.oldFriction = oldFriction;
  const auto specs = ballRollSpecs(options);
  for (std::size_t i = 0; i < specs.size(); ++i) {
    fit.rolls.push_back(rollBall(options.field, specs[i], options.maxSeconds));
    if (options.progress) options.progress(static_cast<int>(i + 1), static_cast<int>(specs.size()));
  }
  fit.friction = fitFriction(fit.rolls);
  for (const BallRoll& r : fit.rolls) {
    fit.endErrors.push_back((predictedEnd(r.spec, fit.friction) - r.end).norm());
    fit.oldEndErrors.push_back((predictedEnd(r.spec, oldFriction) - r.end).norm());
  }
  return fit;
}

nlohmann::json BallRollFit::toJson() const {
  auto r4 = [](double x) { return std::round(x * 1e4) / 1e4; };
  nlohmann::json rollsJson = nlohmann::json::array();
  std::vector<double> fast, slow;
  for (std::size_t i = 0; i < rolls.size(); ++i) {
    const BallRoll& r = rolls[i];
    fast.push_back(r.frictionFast);
    slow.push_back(r.frictionSlow);
    rollsJson.push_back({{"speed_m_s", r4(r.spec.speed)},
                         {"direction_deg", r4(r.spec.direction * 180 / M_PI)},
                         {"start", vec2(r.spec.start)},
                         {"end", vec2(r.end)},
                         {"distance_m", r4(r.distance)},
                         {"seconds", r4(r.seconds)},
                         {"stopped", r.stopped},
                         {"blocked", r.blocked},
                         {"path_bend_deg", r4(r.bend * 180 / M_PI)},
                         {"friction_from_distance_m_s2", r4(r.frictionFromDistance)},
                         {"friction_from_speed_m_s2", r4(r.frictionFromSpeed)},
                         {"friction_above_half_speed_m_s2", r4(r.frictionFast)},
                         {"friction_below_half_speed_m_s2", r4(r.frictionSlow)},
                         {"end_error_m", r4(endErrors[i])},
                         {"end_error_old_m", r4(oldEndErrors[i])}});
  }
  // By nominal direction (the nearest multiple of 45 deg): the deceleration from the distance.
  std::map<int, std::vector<double>> byDirection;
  for (const BallRoll& r : rolls)
    if (!r.blocked && r.stopped) {
      const int deg = static_cast<int>(std::lround(r.spec.direction * 4 / M_PI)) * 45;
      byDirection[(deg + 360) % 360].push_back(r.frictionFromDistance);
    }
  nlohmann::json directions = nlohmann::json::object();
  for (const auto& [deg, v] : byDirection) directions[std::to_string(deg)] = r4(median(v));
  auto stats = [&](const std::vector<double>& e) {
    return nlohmann::json{{"median", r4(median(e))}, {"max", r4(e.empty() ? 0 : *std::max_element(e.begin(), e.end()))}};
  };
  return {{"friction_m_s2", r4(friction)},
          {"old_friction_m_s2", oldFriction},
          {"end_error_m", stats(endErrors)},
          {"end_error_old_m", stats(oldEndErrors)},
          {"deceleration_m_s2",
           {{"above_half_speed_median", r4(median(fast))},
            {"below_half_speed_median", r4(median(slow))},
            {"from_distance_by_direction_deg", directions}}},
          {"rolls", rollsJson}};
}

}  // namespace nao::sim
