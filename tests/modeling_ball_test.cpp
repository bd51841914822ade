// Ball model (perception/modeling/BallFilter) against synthetic truth: a lying ball seen from
// different distances, a rolling ball under a known constant deceleration, the robot walking
// and turning (odometry), balls that should have been seen and were not.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "perception/modeling/BallFilter.h"

namespace nao {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDt = 1.0 / 30;
using Vec2 = Eigen::Vector2d;

// Every generator's seed; --gtest_random_seed=N moves all of them (a robustness sweep with the
// same binary); the default (0) gives the figures in docs/modeling.md.
std::uint64_t seed(std::uint64_t base) {
  return base + 1000003ULL * static_cast<std::uint64_t>(::testing::GTEST_FLAG(random_seed));
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? std::numeric_limits<double>::quiet_NaN() : v[v.size() / 2];
}

// A percept of the true ball (robot frame) with noise growing with distance, and the
// covariance the vision would state for it.
BallObservation observe(const Vec2& truth, std::mt19937_64& rng, double base = 0.01, double perMetre = 0.02) {
  const double s = base + perMetre * truth.norm();
  std::normal_distribution<double> n(0, s);
  BallObservation o;
  o.position = truth + Vec2(n(rng), n(rng));
  o.covariance = Eigen::Matrix2d::Identity() * s * s;
  return o;
}

// The true rolling ball: constant deceleration `mu` along its path.
struct RollingBall {
  Vec2 p, v;
  double mu;
  void step(double dt) {
    const double s = v.norm();
    if (s <= 0) return;
    const double ds = std::max(0.0, s - mu * dt);
    const double t = std::min(dt, s / mu);
    p += v / s * (s * t - 0.5 * mu * t * t);
    v = v / s * ds;
  }
  Vec2 end() const { return p + v * (v.norm() / (2 * mu)); }
};

TEST(BallFilter, LyingBallErrorByDistance) {
  std::mt19937_64 rng(seed(1));
  std::vector<double> near, far;
  for (int trial = 0; trial < 40; ++trial) {
    std::uniform_real_distribution<double> u(0, 1);
    const double d = trial < 20 ? 0.3 + 1.7 * u(rng) : 2.0 + 2.0 * u(rng);
    const double a = (u(rng) - 0.5) * kPi / 2;
    const Vec2 truth(d * std::cos(a), d * std::sin(a));
    BallFilter f;
    BallModel m;
    for (int i = 0; i < 30; ++i) {
      BallInput in;
      in.time = i * kDt;
      in.observations = {observe(truth, rng)};
      in.ballExpectedInView = true;
      m = f.update(in);
    }
    ASSERT_TRUE(m.valid);
    EXPECT_FALSE(m.rolling);
    (trial < 20 ? near : far).push_back((m.position - truth).norm());
  }
  std::printf("lying ball after 1 s: median error %.4f m at 0-2 m, %.4f m at 2-4 m\n", median(near), median(far));
  EXPECT_LT(median(near), 0.03);
  EXPECT_LT(median(far), 0.08);
}

// A kicked ball: the end position predicted after 0.4 s and after 1 s of percepts, with the
// true friction; with a wrong friction the same prediction misses (the test can fail).
TEST(BallFilter, RollingBallEndPosition) {
  const double mu = 0.4;
  struct Result {
    std::vector<double> early, late;
    int rollingSelected = 0;
  };
  auto run = [&](double filterFriction, std::uint64_t seed) {
    Result r;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    for (int trial = 0; trial < 30; ++trial) {
      BallFilter::Params prm;
      prm.friction = filterFriction;
      BallFilter f(prm);
      // Lying 1 s, then kicked for 1-4 m (speed sqrt(2 mu d)).
      const Vec2 start(0.5 + u(rng), (u(rng) - 0.5));
      const double dist = 1.0 + 3.0 * u(rng), dir = (u(rng) - 0.5) * 1.2;
      RollingBall ball{start, Vec2::Zero(), mu};
      double t = 0;
      BallModel m;
      for (int i = 0; i < 30; ++i, t += kDt) {
        BallInput in;
        in.time = t;
        in.observations = {observe(ball.p, rng)};
        m = f.update(in);
      }
      ball.v = std::sqrt(2 * mu * dist) * Vec2(std::cos(dir), std::sin(dir));
      const Vec2 trueEnd = ball.end();
      for (int i = 1; i <= 30; ++i, t += kDt) {
        ball.step(kDt);
        BallInput in;
        in.time = t + kDt;
        in.observations = {observe(ball.p, rng)};
        m = f.update(in);
        if (i == 12) {
          r.early.push_back((m.endPosition - trueEnd).norm());
          if (m.rolling) ++r.rollingSelected;
        }
      }
      r.late.push_back((m.endPosition - trueEnd).norm());
    }
    return r;
  };
  const Result right = run(mu, seed(2)), wrong = run(2 * mu, seed(2));
  std::printf("rolling ball (30 kicks of 1-4 m, friction %.2f m/s^2), end position: median error %.3f m after 0.4 s, "
              "%.3f m (max %.3f) after 1 s; with the friction doubled %.3f m after 1 s; rolling selected at 0.4 s %d/30\n",
              mu, median(right.early), median(right.late), *std::max_element(right.late.begin(), right.late.end()),
              median(wrong.late), right.rollingSelected);
  EXPECT_GE(right.rollingSelected, 28);
  EXPECT_LT(median(right.late), 0.20);
  EXPECT_LT(median(right.early), 0.5);
  EXPECT_GT(median(wrong.late), 0.4);
}

TEST(BallFilter, RollingBallComesToRestAsLying) {
  std::mt19937_64 rng(seed(3));
  const double mu = 0.4;
  RollingBall ball{{1.0, 0.0}, {1.2, 0.3}, mu};
  BallFilter::Params prm;
  prm.friction = mu;
  BallFilter f(prm);
  BallModel m;
  double t = 0;
  bool sawRolling = false;
  for (int i = 0; i < 180; ++i, t += kDt) {
    ball.step(kDt);
    BallInput in;
    in.time = t;
    in.observations = {observe(ball.p, rng)};
    m = f.update(in);
    sawRolling = sawRolling || m.rolling;
  }
  EXPECT_TRUE(sawRolling);
  EXPECT_FALSE(m.rolling);
  EXPECT_LT((m.position - ball.p).norm(), 0.05);
  EXPECT_LT((m.endPosition - ball.p).norm(), 0.05);
}

TEST(BallFilter, PhysicsHelpers) {
  const double mu = 0.5;
  const Vec2 p(1, 2), v(2, 0);
  EXPECT_NEAR((BallFilter::endPosition(p, v, mu) - Vec2(1 + 4.0 / (2 * mu), 2)).norm(), 0, 1e-12);
  // s = v t - mu t^2 / 2: after 1 s, 2 - 0.25 = 1.75 m; the speed 1.5 m/s.
  EXPECT_NEAR((BallFilter::positionAfter(p, v, 1.0, mu) - Vec2(2.75, 2)).norm(), 0, 1e-12);
  EXPECT_NEAR(BallFilter::velocityAfter(v, 1.0, mu).x(), 1.5, 1e-12);
  EXPECT_NEAR((BallFilter::positionAfter(p, v, 100.0, mu) - BallFilter::endPosition(p, v, mu)).norm(), 0, 1e-12);
  EXPECT_NEAR(BallFilter::timeToTravel(2.0, 1.75, mu), 1.0, 1e-12);
  EXPECT_TRUE(std::isinf(BallFilter::timeToTravel(2.0, 4.5, mu)));  // stops after 4 m
  // On the model: the rolling ball's time to a point on its path.
  std::mt19937_64 rng(seed(4));
  BallFilter::Params prm;
  prm.friction = mu;
  BallFilter f(prm);
  RollingBall ball{{0.5, 0.0}, {2.0, 0.0}, mu};
  double t = 0;
  for (int i = 0; i < 15; ++i, t += kDt) {
    ball.step(kDt);
    BallInput in;
    in.time = t;
    in.observations = {observe(ball.p, rng, 0.005, 0.005)};
    f.update(in);
  }
  ASSERT_TRUE(f.model().rolling);
  const Vec2 target = ball.p + Vec2(1.0, 0);
  // The true time: speed s now, 1 m further.
  const double truth = BallFilter::timeToTravel(ball.v.norm(), 1.0, mu);
  std::printf("time to a point 1 m ahead: model %.3f s, truth %.3f s\n", f.timeToReach(target), truth);
  EXPECT_NEAR(f.timeToReach(target), truth, 0.1);
}

TEST(BallFilter, LostAfterNFramesExpectedButUnseen) {
  std::mt19937_64 rng(seed(5));
  BallFilter f;
  const int n = f.params().lostAfterFrames;
  const Vec2 truth(1.5, 0.2);
  double t = 0;
  auto cycle = [&](bool seen, bool expected) {
    BallInput in;
    in.time = t;
    if (seen) in.observations = {observe(truth, rng)};
    in.ballExpectedInView = expected;
    t += kDt;
    return f.update(in);
  };
  for (int i = 0; i < 20; ++i) cycle(true, true);
  ASSERT_FALSE(f.model().lost);
  const double seen = f.model().seenTime;
  // Not in view: not lost until lostAfterSeconds have passed unseen.
  for (int i = 0; i < 100; ++i) EXPECT_FALSE(cycle(false, false).lost);
  {
    BallFilter g;
    double tg = 0;
    for (int i = 0; i < 10; ++i, tg += kDt) g.update({tg, {}, {observe(truth, rng)}, true, {}});
    const double lastSeen = g.model().seenTime;
    for (; tg - lastSeen < g.params().lostAfterSeconds - 0.05; tg += kDt) ASSERT_FALSE(g.update({tg, {}, {}, false, {}}).lost);
    for (; tg - lastSeen < g.params().lostAfterSeconds + 0.05; tg += kDt) g.update({tg, {}, {}, false, {}});
    EXPECT_TRUE(g.model().lost);
    EXPECT_TRUE(g.model().valid);  // still the last known position
  }
  // In view but unseen: lost at exactly the n-th frame.
  for (int i = 1; i <= n; ++i) {
    const BallModel m = cycle(false, true);
    EXPECT_EQ(m.lost, i >= n) << "frame " << i;
    EXPECT_EQ(m.unseenFrames, i);
  }
  EXPECT_DOUBLE_EQ(f.model().seenTime, seen);
  EXPECT_TRUE(f.model().valid);  // still the last known position
  // Seen again: found.
  const BallModel m = cycle(true, true);
  EXPECT_FALSE(m.lost);
  EXPECT_EQ(m.unseenFrames, 0);
}

TEST(BallFilter, OdometryMovesTheRelativeBall) {
  std::mt19937_64 rng(seed(6));
  BallFilter f;
  const Vec2 fieldBall(2.0, 1.0);
  Pose2 robot(0, 0, 0);
  double t = 0;
  for (int i = 0; i < 30; ++i, t += kDt) {
    BallInput in;
    in.time = t;
    in.observations = {observe(robot.inverse() * fieldBall, rng, 0.002, 0.0)};
    f.update(in);
  }
  // Walk 1 m on a curve, turning 90 deg, without seeing the ball; exact odometry.
  for (int i = 0; i < 120; ++i, t += kDt) {
    const Pose2 d(1.0 / 120, 0.2 / 120, (kPi / 2) / 120);
    robot = robot * d;
    BallInput in;
    in.time = t;
    in.odometryDelta = d;
    in.robotPose = robot;
    f.update(in);
  }
  const Vec2 truth = robot.inverse() * fieldBall;
  const BallModel m = f.model();
  std::printf("after 1 m and 90 deg unseen: relative ball error %.4f m (ball at %.2f, %.2f), field error %.4f m\n",
              (m.position - truth).norm(), truth.x(), truth.y(), (m.fieldPosition - fieldBall).norm());
  EXPECT_LT((m.position - truth).norm(), 0.01);
  ASSERT_TRUE(m.fieldValid);
  EXPECT_LT((m.fieldPosition - fieldBall).norm(), 0.01);
  // The covariance grew with the walk.
  EXPECT_GT(m.covariance(0, 0) + m.covariance(1, 1), 1e-3);
  // Without the odometry the model would be far off: the correction is real.
  EXPECT_GT((robot.inverse() * fieldBall - fieldBall).norm(), 0.5);
}

TEST(BallFilter, FieldCoordinatesOfARollingBall) {
  std::mt19937_64 rng(seed(7));
  const double mu = 0.4;
  BallFilter::Params prm;
  prm.friction = mu;
  BallFilter f(prm);
  const Pose2 robot(1.0, -2.0, kPi / 2);
  RollingBall ball{{1.0, 0.0}, {1.5, 0.0}, mu};  // robot frame
  double t = 0;
  BallModel m;
  for (int i = 0; i < 30; ++i, t += kDt) {
    ball.step(kDt);
    BallInput in;
    in.time = t;
    in.observations = {observe(ball.p, rng, 0.005, 0.005)};
    in.robotPose = robot;
    m = f.update(in);
  }
  ASSERT_TRUE(m.rolling && m.fieldValid);
  // The field values are the robot-frame ones moved by the pose ...
  EXPECT_LT((m.fieldPosition - robot * m.position).norm(), 1e-9);
  EXPECT_LT((m.fieldEndPosition - robot * m.endPosition).norm(), 1e-9);
  EXPECT_NEAR(m.fieldVelocity.x(), -m.velocity.y(), 1e-9);  // robot x is field +y, robot y field -x
  EXPECT_NEAR(m.fieldVelocity.y(), m.velocity.x(), 1e-9);
  // ... and near the truth.
  EXPECT_LT((m.fieldPosition - robot * ball.p).norm(), 0.03);
  EXPECT_NEAR(m.fieldVelocity.x(), 0, 0.25);
  EXPECT_NEAR(m.fieldVelocity.y(), ball.v.x(), 0.25);
  EXPECT_LT((m.fieldEndPosition - robot * ball.end()).norm(), 0.4);
}

// A false ball now and then does not move the lying ball's model.
TEST(BallFilter, OutliersDoNotMoveTheLyingBall) {
  std::mt19937_64 rng(seed(8));
  BallFilter f;
  const Vec2 truth(1.2, -0.4);
  std::uniform_real_distribution<double> u(-3, 3);
  double t = 0;
  std::vector<double> errs;
  for (int i = 0; i < 150; ++i, t += kDt) {
    BallInput in;
    in.time = t;
    in.observations = {observe(truth, rng)};
    if (i % 10 == 5) in.observations.push_back({Vec2(u(rng) + 3.5, u(rng)), Eigen::Matrix2d::Identity() * 0.01});
    const BallModel m = f.update(in);
    if (i > 30) errs.push_back((m.position - truth).norm());
  }
  std::printf("lying ball with a false ball every 10th frame: median error %.4f m, max %.4f m\n", median(errs),
              *std::max_element(errs.begin(), errs.end()));
  EXPECT_LT(*std::max_element(errs.begin(), errs.end()), 0.05);
}

// A false percept now and then is never the ball, even at the same spot (a penalty mark taken
// for a ball every second): not before the ball was seen, not while it is remembered out of
// view; it neither moves the ball nor counts as seeing it. A ball seen in confirmPercepts
// images within confirmWindow is.
TEST(BallFilter, ASingleFalsePerceptIsNeverTheBall) {
  std::mt19937_64 rng(seed(9));
  BallFilter f;
  const int confirm = f.params().confirmPercepts;
  ASSERT_GE(confirm, 2);
  double t = 0;
  auto cycle = [&](std::vector<BallObservation> obs, bool expected = false) {
    BallInput in;
    in.time = t;
    in.observations = std::move(obs);
    in.ballExpectedInView = expected;
    t += kDt;
    return f.update(in);
  };
  const BallObservation falseBall{Vec2(3.0, -1.0), Eigen::Matrix2d::Identity() * 0.01};
  EXPECT_FALSE(cycle({falseBall}).valid);
  for (int i = 0; i < 10; ++i) EXPECT_FALSE(cycle({}).valid);
  // The true ball: the model only from the confirming percept on.
  const Vec2 truth(1.0, 0.5);
  for (int i = 1; i <= confirm; ++i) EXPECT_EQ(cycle({observe(truth, rng)}).valid, i >= confirm) << "percept " << i;
  for (int i = 0; i < 10; ++i) cycle({observe(truth, rng)});
  const double seen = f.model().seenTime;
  // Remembered out of view; a false percept elsewhere, now and then.
  for (int i = 0; i < 200; ++i) {
    const BallModel m = cycle(i % 40 == 0 ? std::vector<BallObservation>{falseBall} : std::vector<BallObservation>{});
    ASSERT_TRUE(m.valid);
    EXPECT_LT((m.position - truth).norm(), 0.05) << i;
    EXPECT_DOUBLE_EQ(m.seenTime, seen) << i;
  }
  // In view, unseen, while scattered false percepts come elsewhere: lost all the same.
  for (int i = 0; i < f.params().lostAfterFrames; ++i)
    cycle({{Vec2(3.0 + 0.7 * i, -1.0 - 0.5 * i), Eigen::Matrix2d::Identity() * 0.01}}, true);
  EXPECT_TRUE(f.model().valid);
  EXPECT_TRUE(f.model().lost);
  EXPECT_LT((f.model().position - truth).norm(), 0.05);
}

TEST(BallFilter, NonFiniteInputsAreSkipped) {
  std::mt19937_64 rng(seed(9));
  BallFilter f;
  const Vec2 truth(1.0, 0.5);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  double t = 0;
  for (int i = 0; i < 90; ++i, t += kDt) {
    BallInput in;
    in.time = (i % 9 == 4) ? nan : t;
    in.observations = {observe(truth, rng)};
    if (i % 5 == 2) in.observations.push_back({Vec2(nan, 1), Eigen::Matrix2d::Identity()});
    if (i % 5 == 3) in.observations.push_back({Vec2(1e300, inf), Eigen::Matrix2d::Identity()});
    if (i % 7 == 1) in.odometryDelta = Pose2(nan, 0, inf);
    if (i % 7 == 2) in.odometryDelta = Pose2(40, 0, 0);
    if (i % 6 == 0) in.observations.front().covariance(0, 1) = nan;  // unusable covariance: default noise
    if (i % 8 == 0) in.robotPose = Pose2(nan, 0, 0);
    const BallModel m = f.update(in);
    ASSERT_TRUE(m.position.allFinite() && m.velocity.allFinite() && m.covariance.allFinite() &&
                m.endPosition.allFinite())
        << "frame " << i;
    if (i % 8 == 0) {
      EXPECT_FALSE(m.fieldValid);
    }
  }
  EXPECT_LT((f.model().position - truth).norm(), 0.03);
  EXPECT_GT(f.stats().skippedObservations, 30);
  EXPECT_GT(f.stats().skippedOdometry, 20);
  EXPECT_GT(f.stats().skippedTimes, 5);
}

}  // namespace
}  // namespace nao
