// Self-localization (perception/modeling/SelfLocator) against synthetic truth: a true
// trajectory on the real field model, percepts projected from the field's lines,
// intersections, circle and penalty marks into the robot frame (only inside each camera's view
// sector and range), with noise, dropped and false percepts; odometry with noise and a scale
// error. Nothing here reads the filter's model of the field: the generator works from its own
// FieldModel and its own view geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Cholesky>

#include "perception/FieldDimensions.h"
#include "perception/modeling/SelfLocator.h"

namespace nao {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180;
constexpr double kFrameDt = 1.0 / 30;  // both cameras at 30 Hz, one cognition cycle each frame
using Vec2 = Eigen::Vector2d;

double wrap(double a) { return Pose2::wrap(a); }

// Every generator's seed; --gtest_random_seed=N moves all of them (a robustness sweep with the
// same binary); the default (0) gives the figures in docs/modeling.md.
std::uint64_t seed(std::uint64_t base) {
  return base + 1000003ULL * static_cast<std::uint64_t>(::testing::GTEST_FLAG(random_seed));
}

Vec2 toRobot(const Pose2& pose, const Vec2& p) { return pose.inverse() * p; }

struct View {
  double yaw = 0, halfFov = 28 * kDeg, minRange = 0.5, maxRange = 5.0;
  bool sees(const Vec2& p) const {
    const double r = p.norm();
    if (r < minRange || r > maxRange) return false;
    return std::abs(wrap(std::atan2(p.y(), p.x()) - yaw)) <= halfFov;
  }
};

struct Noise {
  double base = 0.02, perMetre = 0.03;
  double sigma(const Vec2& p) const { return base + perMetre * p.norm(); }
};

// Percepts of one camera image, made from the truth.
class PerceptGenerator {
 public:
  explicit PerceptGenerator(const FieldModel& field, std::uint64_t seed) : field_(field), rng_(seed) {}

  double dropRate = 0.2;        // each true percept is lost with this probability
  double falseLineRate = 0.1;   // a false line in this share of images
  double falsePointRate = 0.05; // a false intersection / false penalty mark in this share

  // For each line of the last perceive(): the index of the field line it shows.
  std::vector<int> modelLineOf;

  FieldPercepts perceive(const Pose2& truth, const View& view, const Noise& noise, double time) {
    FieldPercepts out;
    out.time = time;
    out.uncertainty.sigmaBase = noise.base;
    out.uncertainty.sigmaPerMetre = noise.perMetre;
    modelLineOf.clear();
    auto jitter = [&](const Vec2& p) {
      std::normal_distribution<double> n(0, noise.sigma(p));
      return Vec2(p.x() + n(rng_), p.y() + n(rng_));
    };
    // Lines: the longest visible run of each field line.
    for (int li = 0; li < static_cast<int>(field_.lines.size()); ++li) {
      const auto& l = field_.lines[li];
      const double len = (l.to - l.from).norm();
      const int n = std::max(2, static_cast<int>(len / 0.02));
      int bestStart = -1, bestEnd = -1, start = -1;
      for (int i = 0; i <= n; ++i) {
        const Vec2 p = toRobot(truth, l.from + (l.to - l.from) * (static_cast<double>(i) / n));
        const bool vis = view.sees(p);
        if (vis && start < 0) start = i;
        if ((!vis || i == n) && start >= 0) {
          const int end = vis ? i : i - 1;
          if (end - start > bestEnd - bestStart) {
            bestStart = start;
            bestEnd = end;
          }
          start = -1;
        }
      }
      if (bestStart < 0) continue;
      const Vec2 a = toRobot(truth, l.from + (l.to - l.from) * (static_cast<double>(bestStart) / n));
      const Vec2 b = toRobot(truth, l.from + (l.to - l.from) * (static_cast<double>(bestEnd) / n));
      if ((b - a).norm() < 0.3 || drop()) continue;
      LinesPercept::Line line;
      line.imageFrom = line.imageTo = Vec2::Zero();
      line.from = jitter(a);
      line.to = jitter(b);
      out.lines.lines.push_back(line);
      modelLineOf.push_back(li);
    }
    // Intersections, with the lines that form them when those were seen.
    for (const auto& x : field_.intersections) {
      const Vec2 p = toRobot(truth, x.position);
      if (!view.sees(p) || drop()) continue;
      LinesPercept::Intersection i;
      i.type = x.type == FieldIntersection::Type::L   ? LinesPercept::Intersection::Type::L
               : x.type == FieldIntersection::Type::T ? LinesPercept::Intersection::Type::T
                                                      : LinesPercept::Intersection::Type::X;
      i.position = jitter(p);
      std::vector<int> through;
      for (int k = 0; k < static_cast<int>(modelLineOf.size()); ++k) {
        const auto& l = field_.lines[modelLineOf[k]];
        const Vec2 d = (l.to - l.from).normalized();
        const double s = d.dot(x.position - l.from);
        const double off = std::abs(Vec2(-d.y(), d.x()).dot(x.position - l.from));
        if (off < 1e-6 && s > -1e-6 && s < (l.to - l.from).norm() + 1e-6) through.push_back(k);
      }
      if (through.size() == 2) {
        i.line1 = through[0];
        i.line2 = through[1];
      }
      out.lines.intersections.push_back(i);
    }
    // Centre circle: found when its centre is in (a slightly wider) view and not too far.
    {
      const Vec2 c = toRobot(truth, field_.centerCircleCenter);
      View wide = view;
      wide.halfFov += 0.3;
      wide.minRange = 0.3;
      wide.maxRange = std::min(view.maxRange, 4.0);
      if (wide.sees(c) && !drop()) {
        out.lines.circle.found = true;
        out.lines.circle.centre = jitter(c);
        out.lines.circle.radius = field_.centerCircleRadius;
      }
    }
    for (const auto& m : field_.penaltyCrosses) {
      const Vec2 p = toRobot(truth, m);
      if (view.sees(p) && p.norm() < 4.5 && !drop()) out.lines.penaltyMark = jitter(p);
    }
    // False percepts somewhere in the view.
    std::uniform_real_distribution<double> u(0, 1);
    auto randomInView = [&]() {
      const double r = view.minRange + u(rng_) * (view.maxRange - view.minRange);
      const double a = view.yaw + (2 * u(rng_) - 1) * view.halfFov;
      return Vec2(r * std::cos(a), r * std::sin(a));
    };
    if (u(rng_) < falseLineRate) {
      const Vec2 c = randomInView();
      const double a = u(rng_) * kPi, len = 0.3 + 0.7 * u(rng_);
      const Vec2 d(std::cos(a), std::sin(a));
      LinesPercept::Line line;
      line.imageFrom = line.imageTo = Vec2::Zero();
      line.from = c - d * len / 2;
      line.to = c + d * len / 2;
      out.lines.lines.push_back(line);
    }
    if (u(rng_) < falsePointRate) {
      LinesPercept::Intersection i;
      i.type = static_cast<LinesPercept::Intersection::Type>(static_cast<int>(u(rng_) * 3) % 3);
      i.position = randomInView();
      out.lines.intersections.push_back(i);
    }
    if (u(rng_) < falsePointRate && !out.lines.penaltyMark) out.lines.penaltyMark = randomInView();
    return out;
  }

  std::mt19937_64& rng() { return rng_; }

 private:
  bool drop() { return std::uniform_real_distribution<double>(0, 1)(rng_) < dropRate; }
  const FieldModel& field_;
  std::mt19937_64 rng_;
};

// The ground a View surely shows, for FieldPercepts::view (negative information): a convex
// polygon inside its sector (the far arc by chords), counter-clockwise.
std::vector<Vec2> viewPolygon(const View& v) {
  auto at = [](double r, double a) { return Vec2(r * std::cos(a), r * std::sin(a)); };
  std::vector<Vec2> p{at(v.minRange, v.yaw - v.halfFov)};
  constexpr int kArc = 8;
  for (int k = 0; k <= kArc; ++k) p.push_back(at(v.maxRange, v.yaw - v.halfFov + 2 * v.halfFov * k / kArc));
  p.push_back(at(v.minRange, v.yaw + v.halfFov));
  return p;
}

// The two cameras: the top one far and coarse, the bottom one near and fine; the head pans.
// Each image says which ground it surely showed (at most 3 m away), as the robot program's do.
struct Cameras {
  Noise topNoise{0.02, 0.03}, bottomNoise{0.01, 0.02};
  bool negative = true;
  std::vector<FieldPercepts> perceive(PerceptGenerator& gen, const Pose2& truth, double t) const {
    const double yaw = 60 * kDeg * std::sin(2 * kPi * t / 4.0);
    View top{yaw, 28 * kDeg, 0.5, 5.0}, bottom{yaw, 28 * kDeg, 0.15, 1.0};
    std::vector<FieldPercepts> out{gen.perceive(truth, top, topNoise, t), gen.perceive(truth, bottom, bottomNoise, t)};
    if (negative) {
      top.maxRange = 3.0;
      out[0].view = viewPolygon(top);
      out[1].view = viewPolygon(bottom);
    }
    return out;
  }
};

// A walk: a unicycle steered through waypoints at 0.25 m/s, turning at most 0.6 rad/s.
class Walker {
 public:
  Walker(Pose2 start, std::vector<Vec2> waypoints) : pose_(start), wps_(std::move(waypoints)) {}
  bool done() const { return next_ >= wps_.size(); }
  // The true robot-frame step of one frame.
  Pose2 step() {
    if (done()) return {};
    const Vec2 rel = toRobot(pose_, wps_[next_]);
    if (rel.norm() < 0.15) {
      ++next_;
      return {};
    }
    const double bearing = std::atan2(rel.y(), rel.x());
    const double omega = std::clamp(2.0 * bearing, -0.6, 0.6);
    const double v = std::abs(bearing) > 1.0 ? 0.05 : 0.25;
    const Pose2 d(v * kFrameDt, 0.02 * std::sin(3 * t_) * kFrameDt, omega * kFrameDt);
    t_ += kFrameDt;
    pose_ = pose_ * d;
    return d;
  }
  const Pose2& pose() const { return pose_; }
  void teleport(const Pose2& p) { pose_ = p; }
  void setWaypoints(std::vector<Vec2> w) {
    wps_ = std::move(w);
    next_ = 0;
  }

 private:
  Pose2 pose_;
  std::vector<Vec2> wps_;
  std::size_t next_ = 0;
  double t_ = 0;
};

// The odometry the filter is told: scaled (translation +5 %, turn -3 %) and noisy.
struct OdometryModel {
  double transScale = 1.05, rotScale = 0.97, transSigma = 0.0005, rotSigma = 0.001;
  Pose2 measure(const Pose2& d, std::mt19937_64& rng) const {
    std::normal_distribution<double> nt(0, transSigma), nr(0, rotSigma);
    return {d.x * transScale + nt(rng), d.y * transScale + nt(rng), d.theta * rotScale + nr(rng)};
  }
};

double positionError(const Pose2& est, const Pose2& truth) { return std::hypot(est.x - truth.x, est.y - truth.y); }
double headingError(const Pose2& est, const Pose2& truth) { return std::abs(wrap(est.theta - truth.theta)); }
// On the wrong half-field symmetry: near the mirror image of the truth (within 1 m and 45 deg).
bool mirrored(const Pose2& est, const Pose2& truth) {
  const Pose2 m = SelfLocator::mirror(truth);
  return positionError(est, m) < 1.0 && headingError(est, m) < 45 * kDeg;
}
// The mirror image of the truth is nearer than the truth plus a margin (position plus 1 m per
// rad of heading, the filter's own measure when it picks one of a candidate's mirror images).
bool nearerMirror(const Pose2& est, const Pose2& truth, double margin) {
  auto d = [&](const Pose2& t) { return positionError(est, t) + headingError(est, t); };
  return d(SelfLocator::mirror(truth)) < d(truth) + margin;
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(std::min<double>(v.size() - 1, std::floor(q * (v.size() - 1) + 0.5)))];
}

FieldModel standardField() { return FieldModel::from(FieldDimensions::load(std::string(NAO_SOURCE_DIR) + "/config/field_dimensions.json")); }

struct RunFigures {
  std::vector<double> pos, head;
  int frames = 0, mirroredFrames = 0, validFrames = 0, neesInside = 0;
  double posMedian() const { return quantile(pos, 0.5); }
  double posP95() const { return quantile(pos, 0.95); }
  double headMedianDeg() const { return quantile(head, 0.5) / kDeg; }
  double headP95Deg() const { return quantile(head, 0.95) / kDeg; }
};

// Walks the waypoints; figures from frame `warmup` on.
RunFigures walk(SelfLocator& loc, Walker& walker, PerceptGenerator& gen, int warmup, int maxFrames = 4000,
                const OdometryModel& odo = OdometryModel()) {
  Cameras cams;
  RunFigures f;
  double t = 0;
  for (int i = 0; i < maxFrames && !walker.done(); ++i) {
    const Pose2 d = walker.step();
    t += kFrameDt;
    LocalizationInput in;
    in.odometryDelta = odo.measure(d, gen.rng());
    in.percepts = cams.perceive(gen, walker.pose(), t);
    const RobotPose est = loc.update(in);
    ++f.frames;
    if (mirrored(est.pose, walker.pose())) ++f.mirroredFrames;
    if (i < warmup) continue;
    f.pos.push_back(positionError(est.pose, walker.pose()));
    f.head.push_back(headingError(est.pose, walker.pose()));
    if (est.valid) ++f.validFrames;
    const Eigen::Vector3d e(est.pose.x - walker.pose().x, est.pose.y - walker.pose().y,
                            wrap(est.pose.theta - walker.pose().theta));
    if (e.dot(est.covariance.ldlt().solve(e)) <= 7.81) ++f.neesInside;  // chi-square 3 dof, 95 %
  }
  return f;
}

TEST(SelfLocator, TracksAWalkAcrossTheField) {
  const FieldModel field = standardField();
  PerceptGenerator gen(field, seed(11));
  Walker walker({-3.8, -2.2, 0.5}, {{-1.0, 1.5}, {1.5, -1.5}, {3.8, 2.0}});
  SelfLocator loc(field);
  loc.resetTo(walker.pose(), {0.1, 0.1, 0.1});
  const RunFigures f = walk(loc, walker, gen, 60);
  ASSERT_TRUE(walker.done());
  std::printf("walk: %d frames, position median %.3f p95 %.3f max %.3f m, heading median %.2f p95 %.2f deg, valid %.3f, "
              "NEES inside 95%% bound %.3f\n",
              f.frames, f.posMedian(), f.posP95(), quantile(f.pos, 1.0), f.headMedianDeg(), f.headP95Deg(),
              static_cast<double>(f.validFrames) / f.pos.size(), static_cast<double>(f.neesInside) / f.pos.size());
  EXPECT_LT(f.posMedian(), 0.05);
  EXPECT_LT(f.posP95(), 0.15);
  EXPECT_LT(f.headMedianDeg(), 1.5);
  EXPECT_LT(f.headP95Deg(), 5.0);
  EXPECT_EQ(f.mirroredFrames, 0);
  EXPECT_GT(static_cast<double>(f.validFrames) / f.pos.size(), 0.9);
  // The claimed covariance is honest: the error inside its 95 % ellipsoid most of the time.
  EXPECT_GT(static_cast<double>(f.neesInside) / f.pos.size(), 0.8);
}

// Dead reckoning alone drifts: the same walk without percepts is far worse (the percepts carry
// the figures above, not the odometry).
TEST(SelfLocator, WithoutPerceptsTheOdometryErrorGrows) {
  const FieldModel field = standardField();
  Walker walker({-3.8, -2.2, 0.5}, {{-1.0, 1.5}, {1.5, -1.5}, {3.8, 2.0}});
  SelfLocator loc(field);
  loc.resetTo(walker.pose(), {0.1, 0.1, 0.1});
  std::mt19937_64 rng(seed(5));
  OdometryModel odo;
  double err = 0;
  for (int i = 0; i < 4000 && !walker.done(); ++i) {
    const Pose2 d = walker.step();
    LocalizationInput in;
    in.odometryDelta = odo.measure(d, rng);
    err = positionError(loc.update(in).pose, walker.pose());
  }
  std::printf("odometry only: final position error %.3f m\n", err);
  EXPECT_GT(err, 0.3);
  EXPECT_FALSE(loc.estimate().valid);
}

// The robot walks in at a side line of its own half (where along it, the filter is not told).
TEST(SelfLocator, ConvergesFromSidelineEntry) {
  const FieldModel field = standardField();
  const double hw = field.halfWidth();
  std::vector<int> framesToConverge;
  int trial = 0;
  for (double sy : {1.0, -1.0})
    for (double x : {-0.8, -2.2, -3.6}) {
      PerceptGenerator gen(field, seed(100 + trial++));
      const Pose2 start(x, sy * (hw + 0.05), -sy * (kPi / 2 - 5 * kDeg));
      Walker walker(start, {{x + 0.3, sy * (hw - 1.5)}, {x + 1.5, sy * (hw - 2.0)}});
      SelfLocator loc(field);
      loc.resetToSidelineEntry(true);
      Cameras cams;
      int converged = -1, mirroredFrames = 0;
      double finalErr = 0;
      double t = 0;
      for (int i = 0; i < 450; ++i) {
        const Pose2 d = walker.step();
        t += kFrameDt;
        LocalizationInput in;
        in.odometryDelta = OdometryModel().measure(d, gen.rng());
        in.percepts = cams.perceive(gen, walker.pose(), t);
        const RobotPose est = loc.update(in);
        const bool ok = positionError(est.pose, walker.pose()) < 0.1 && headingError(est.pose, walker.pose()) < 3 * kDeg;
        if (ok && converged < 0) converged = i;
        if (!ok) converged = -1;  // must stay converged
        if (mirrored(est.pose, walker.pose())) ++mirroredFrames;
        finalErr = positionError(est.pose, walker.pose());
      }
      std::printf("sideline entry x %.1f side %+.0f: converged (and stayed) from frame %d, final error %.3f m\n", x, sy,
                  converged, finalErr);
      EXPECT_GE(converged, 0) << "x " << x << " side " << sy;
      EXPECT_LE(converged, 150) << "x " << x << " side " << sy;  // 5 s
      EXPECT_EQ(mirroredFrames, 0);
      framesToConverge.push_back(converged < 0 ? 9999 : converged);
    }
  std::printf("sideline entry: frames to converge median %.0f max %.0f\n", quantile({framesToConverge.begin(), framesToConverge.end()}, 0.5),
              quantile({framesToConverge.begin(), framesToConverge.end()}, 1.0));
}

// Lifted and set down while walking; the filter is not told. Three fixed kidnaps of 2 m and
// 90 deg, then random ones of 1-3 m and 45-180 deg (as the evaluation's), each set down where
// the true pose is clearly nearer the old estimate than its mirror image is (by 1 m in the
// filter's measure; otherwise nothing on the field can tell the two apart and the filter takes
// the nearer one by design).
TEST(SelfLocator, RecoversFromKidnapping) {
  const FieldModel field = standardField();
  const double hl = field.halfLength(), hw = field.halfWidth();
  std::mt19937_64 rng(seed(42));
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> recovery;
  int trials = 0, recoveredTrials = 0, undrawable = 0;
  for (int trial = 0; trial < 15; ++trial) {
    PerceptGenerator gen(field, seed(200 + trial));
    // Start somewhere inside, walk 5 s towards a random point.
    auto randomPoint = [&](double margin) {
      return Vec2((2 * u(rng) - 1) * (hl - margin), (2 * u(rng) - 1) * (hw - margin));
    };
    const Vec2 s0 = randomPoint(1.0);
    const Pose2 start(s0.x(), s0.y(), (2 * u(rng) - 1) * kPi);
    Walker walker(start, {randomPoint(1.0), randomPoint(1.0)});
    SelfLocator loc(field);
    loc.resetTo(start, {0.1, 0.1, 0.1});
    Cameras cams;
    double t = 0;
    auto cycle = [&]() {
      const Pose2 d = walker.step();
      t += kFrameDt;
      LocalizationInput in;
      in.odometryDelta = OdometryModel().measure(d, gen.rng());
      in.percepts = cams.perceive(gen, walker.pose(), t);
      return loc.update(in);
    };
    for (int i = 0; i < 150; ++i) cycle();
    ASSERT_LT(positionError(loc.estimate().pose, walker.pose()), 0.1);
    const Pose2 before = walker.pose();
    // The kidnap: 2 m / 90 deg for the first three, then 1-3 m / 45-180 deg. Near the centre
    // no such kidnap is clear of the mirror image; the trial is then drawn again.
    Pose2 to;
    bool drawn = false;
    for (int attempt = 0; attempt < 1000 && !drawn; ++attempt) {
      const double dist = trial < 3 ? 2.0 : 1.0 + 2.0 * u(rng);
      const double turn = (trial < 3 ? kPi / 2 : (45 + 135 * u(rng)) * kDeg) * (u(rng) < 0.5 ? -1 : 1);
      const double dir = (2 * u(rng) - 1) * kPi;
      to = Pose2(before.x + dist * std::cos(dir), before.y + dist * std::sin(dir), wrap(before.theta + turn));
      const Pose2 est = loc.estimate().pose;
      drawn = std::abs(to.x) < hl - 0.5 && std::abs(to.y) < hw - 0.5 && !nearerMirror(est, to, 1.0);
    }
    if (!drawn) {
      ++undrawable;
      --trial;
      ASSERT_LT(undrawable, 10);
      continue;
    }
    walker.teleport(to);
    walker.setWaypoints({randomPoint(1.0), randomPoint(1.0)});
    const double jump = positionError(before, to), turned = headingError(before, to);
    int recovered = -1, firstOk = -1;
    double errRightAfter = 0;
    for (int i = 0; i < 450; ++i) {
      const RobotPose est = cycle();
      const bool ok = positionError(est.pose, walker.pose()) < 0.2 && headingError(est.pose, walker.pose()) < 5 * kDeg;
      if (i == 0) errRightAfter = positionError(est.pose, walker.pose());
      if (ok && recovered < 0) recovered = i;
      if (ok && firstOk < 0) firstOk = i;
      if (!ok) recovered = -1;  // must stay recovered to the end
    }
    std::printf("kidnap %.2f m / %.0f deg: error right after %.2f m, back under 0.2 m / 5 deg (and stayed) after %d "
                "updates (%.1f s; first under after %d), final error %.2f m, resets %d\n",
                jump, turned / kDeg, errRightAfter, recovered, recovered * kFrameDt, firstOk,
                positionError(loc.estimate().pose, walker.pose()), loc.stats().resets);
    EXPECT_GT(errRightAfter, 0.9);  // the filter was not told
    if (trial < 3) {
      EXPECT_GE(recovered, 0) << "trial " << trial;
      EXPECT_LE(recovered, 300) << "trial " << trial;  // 10 s of images
    }
    ++trials;
    if (recovered >= 0 && recovered <= 300) ++recoveredTrials;
    recovery.push_back(recovered < 0 ? 9999 : recovered);
  }
  std::printf("kidnap: %d/%d recovered within 300 updates (10 s), updates to recover median %.0f p95 %.0f\n",
              recoveredTrials, trials, quantile(recovery, 0.5), quantile(recovery, 0.95));
  EXPECT_GE(recoveredTrials, trials - 1);  // >= 93 % of 15
  EXPECT_LE(quantile(recovery, 0.5), 150);  // median <= 5 s
}

// Started from the game situation (a penalised robot returns beside its own penalty mark), the
// robot crosses the centre circle into the opponent half: never on the mirrored pose.
TEST(SelfLocator, NoMirroredPoseFromPenaltyReturn) {
  const FieldModel field = standardField();
  const double hl = field.halfLength(), hw = field.halfWidth();
  int trial = 0;
  for (double sy : {1.0, -1.0}) {
    PerceptGenerator gen(field, seed(300 + trial++));
    const Pose2 start(-hl + 1.3 + 0.25 * sy, sy * hw, -sy * kPi / 2);
    Walker walker(start, {{-hl + 1.6, sy * (hw - 1.0)}, {-0.3, 0.2 * sy}, {1.5, -0.8 * sy}, {2.8, 0.5}});
    SelfLocator loc(field);
    loc.resetToPenaltyReturn();
    const RunFigures f = walk(loc, walker, gen, 150);
    std::printf("penalty return side %+.0f: %d frames, mirrored %d, position median %.3f m\n", sy, f.frames,
                f.mirroredFrames, f.posMedian());
    EXPECT_TRUE(walker.done());
    EXPECT_EQ(f.mirroredFrames, 0);
    EXPECT_LT(f.posMedian(), 0.05);
  }
}

// The mirror test above can fail: a filter started on the wrong half stays there (the field
// alone cannot tell), which is why the game situation must decide.
TEST(SelfLocator, StartedMirroredItStaysMirrored) {
  const FieldModel field = standardField();
  PerceptGenerator gen(field, seed(400));
  Walker walker({-2.0, -1.0, 0.4}, {{-0.5, 0.3}, {1.0, 0.5}});
  SelfLocator loc(field);
  loc.resetTo(SelfLocator::mirror(walker.pose()), {0.1, 0.1, 0.1});
  const RunFigures f = walk(loc, walker, gen, 0);
  EXPECT_GT(f.mirroredFrames, f.frames * 9 / 10);
}

TEST(SelfLocator, NonFiniteAndAbsurdInputsAreSkipped) {
  const FieldModel field = standardField();
  PerceptGenerator gen(field, seed(500));
  Walker walker({-3.0, 1.0, -0.3}, {{0.0, -1.0}, {2.0, 1.0}});
  SelfLocator loc(field);
  loc.resetTo(walker.pose(), {0.1, 0.1, 0.1});
  Cameras cams;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  std::vector<double> errs;
  double t = 0;
  int bad = 0, badOdometry = 0;
  auto finiteState = [&]() {
    for (const auto& h : loc.hypotheses())
      if (!h.mean.allFinite() || !h.cov.allFinite()) return false;
    const RobotPose e = loc.estimate();
    return std::isfinite(e.pose.x) && std::isfinite(e.pose.y) && std::isfinite(e.pose.theta) &&
           e.covariance.allFinite() && std::isfinite(e.quality);
  };
  for (int i = 0; i < 900 && !walker.done(); ++i) {
    const Pose2 d = walker.step();
    t += kFrameDt;
    LocalizationInput in;
    in.odometryDelta = OdometryModel().measure(d, gen.rng());
    in.percepts = cams.perceive(gen, walker.pose(), t);
    if (i % 7 == 3) {
      // Garbage beside the good percepts.
      FieldPercepts g;
      g.time = t;
      LinesPercept::Line l;
      l.imageFrom = l.imageTo = Vec2::Zero();
      l.from = Vec2(nan, 1);
      l.to = Vec2(2, 1);
      g.lines.lines.push_back(l);
      l.from = Vec2(1e300, -1e300);
      l.to = Vec2(1, inf);
      g.lines.lines.push_back(l);
      LinesPercept::Intersection x;
      x.position = Vec2(inf, 0);
      x.line1 = 0;
      x.line2 = 1;
      g.lines.intersections.push_back(x);
      g.lines.circle.found = true;
      g.lines.circle.centre = Vec2(nan, nan);
      g.lines.penaltyMark = Vec2(-inf, 3);
      in.percepts.push_back(g);
      FieldPercepts late = in.percepts.front();
      late.time = nan;
      in.percepts.push_back(late);
      ++bad;
    }
    loc.update(in);
    ASSERT_TRUE(finiteState()) << "frame " << i;
    if (i % 11 == 5) {
      // A NaN odometry step, an infinite one and an absurd one, each its own cycle.
      for (const Pose2& o : {Pose2(nan, 0, 0), Pose2(0, 0, inf), Pose2(30, 0, 0), Pose2(0, 0, 9)}) {
        ++badOdometry;
        LocalizationInput g;
        g.odometryDelta = o;
        g.gyroZ = nan;
        loc.update(g);
        ASSERT_TRUE(finiteState()) << "frame " << i;
      }
    }
    if (i > 60) errs.push_back(positionError(loc.estimate().pose, walker.pose()));
  }
  // resetTo with NaN is refused too.
  loc.resetTo(Pose2(nan, 0, 0), {0.1, 0.1, 0.1});
  ASSERT_TRUE(finiteState());
  const auto& s = loc.stats();
  std::printf("garbage: %d bad percept sets, skipped odometry %d, percept elements %d, sets %d; position median %.3f m\n",
              bad, s.skippedOdometry, s.skippedPercepts, s.skippedSets, quantile(errs, 0.5));
  EXPECT_EQ(s.skippedOdometry, badOdometry);
  EXPECT_GE(s.skippedPercepts, 5 * bad);
  EXPECT_EQ(s.skippedSets, bad);
  EXPECT_EQ(s.skippedResets, 1);
  EXPECT_EQ(s.reinitialisations, 0);
  EXPECT_LT(quantile(errs, 0.5), 0.05);
}

TEST(SelfLocator, WorksOnTheReducedField) {
  const FieldModel reduced =
      FieldModel::from(FieldDimensions::load(std::string(NAO_SOURCE_DIR) + "/config/field_dimensions_reduced.json"));
  ASSERT_LT(reduced.halfLength(), 4.0);
  const std::vector<Vec2> route = {{-1.0, 1.2}, {1.2, -1.2}, {3.0, 1.5}};
  {
    PerceptGenerator gen(reduced, seed(600));
    Walker walker({-3.2, -1.8, 0.5}, route);
    SelfLocator loc(reduced);
    loc.resetToSidelineEntry(true);
    walker.teleport({-2.0, -reduced.halfWidth(), kPi / 2});
    walker.setWaypoints({{-2.0, -1.0}, {-1.0, 1.2}, {1.2, -1.2}, {3.0, 1.5}});
    const RunFigures f = walk(loc, walker, gen, 150);
    std::printf("reduced field: %d frames, position median %.3f p95 %.3f m, heading median %.2f deg, mirrored %d\n",
                f.frames, f.posMedian(), f.posP95(), f.headMedianDeg(), f.mirroredFrames);
    EXPECT_TRUE(walker.done());
    EXPECT_LT(f.posMedian(), 0.05);
    EXPECT_LT(f.headMedianDeg(), 1.5);
    EXPECT_EQ(f.mirroredFrames, 0);
  }
  {
    // The filter's field matters: built from the standard field, it cannot track the reduced one.
    PerceptGenerator gen(reduced, seed(601));
    Walker walker({-3.2, -1.8, 0.5}, route);
    SelfLocator loc(standardField());
    loc.resetTo(walker.pose(), {0.1, 0.1, 0.1});
    const RunFigures f = walk(loc, walker, gen, 150);
    std::printf("reduced field seen with the standard field's model: position median %.3f m\n", f.posMedian());
    EXPECT_GT(f.posMedian(), 0.15);
  }
}

// Candidate poses from feature combinations, from exact percepts at known poses.
TEST(SelfLocator, FeatureCandidatesMatchTheTruth) {
  const FieldModel field = standardField();
  SelfLocator loc(field);
  PerceptGenerator gen(field, seed(700));
  gen.dropRate = 0;
  gen.falseLineRate = 0;
  gen.falsePointRate = 0;
  const Noise exact{0.0, 0.0};
  struct Case {
    const char* what;
    Pose2 truth;
    View view;
  };
  const std::vector<Case> cases = {
      {"circle + halfway line", {-1.8, 0.4, 0.1}, {0, 28 * kDeg, 0.3, 3.0}},
      {"penalty mark + penalty-area line", {-1.5, -0.3, kPi - 0.1}, {0, 28 * kDeg, 0.3, 3.0}},
      {"goal-box corner (penalty mark hidden)", {-2.6, 0.6, kPi - 0.3}, {0, 28 * kDeg, 0.3, 2.5}},
      {"goal box side view (lines only)", {-4.0, -2.7, 95 * kDeg}, {0, 28 * kDeg, 0.3, 2.5}},
  };
  for (const auto& c : cases) {
    FieldPercepts p = gen.perceive(c.truth, c.view, exact, 0);
    if (std::string(c.what).find("corner") != std::string::npos) {
      p.lines.penaltyMark.reset();
      p.lines.circle.found = false;
    }
    if (std::string(c.what).find("side view") != std::string::npos) {
      // The goal box seen from the side, as the vision reports it; nothing else but lines.
      auto indexOf = [&](const std::string& name) {
        for (std::size_t k = 0; k < gen.modelLineOf.size(); ++k)
          if (field.lines[gen.modelLineOf[k]].name == name) return static_cast<int>(k);
        return -1;
      };
      p.lines.goalBoxSide.found = true;
      p.lines.goalBoxSide.shortLine = indexOf("own_goal_box_right");
      p.lines.goalBoxSide.longLine1 = indexOf("own_goal_line");
      p.lines.goalBoxSide.longLine2 = indexOf("own_goal_box_front");
      ASSERT_GE(p.lines.goalBoxSide.shortLine, 0);
      ASSERT_GE(p.lines.goalBoxSide.longLine1, 0);
      ASSERT_GE(p.lines.goalBoxSide.longLine2, 0);
      p.lines.intersections.clear();
      p.lines.penaltyMark.reset();
      p.lines.circle.found = false;
    }
    p.uncertainty.sigmaBase = 0.02;
    const std::vector<Pose2> cands = loc.featureCandidates(p);
    bool found = false;
    for (const auto& q : cands) {
      for (const Pose2& m : {q, SelfLocator::mirror(q)})
        found = found || (positionError(m, c.truth) < 0.02 && headingError(m, c.truth) < 1 * kDeg);
    }
    std::printf("%s: %zu candidates, truth among them: %s\n", c.what, cands.size(), found ? "yes" : "no");
    EXPECT_TRUE(found) << c.what;
    // Every candidate is the truth (or its mirror): nothing else passes verification.
    for (const auto& q : cands)
      EXPECT_LT(std::min(positionError(q, c.truth), positionError(SelfLocator::mirror(q), c.truth)), 0.05) << c.what;
  }
}

// Negative information: a hypothesis that puts the centre circle and the halfway line right in
// front of the robot, while its images show only the empty ground beyond a side line, loses
// its validity; without the images' views it could not (no percept contradicts it), and the
// true pose, which expects nothing there, keeps it.
TEST(SelfLocator, AHypothesisWhoseLinesTheImagesDoNotShowLosesItsValidity) {
  const FieldModel field = standardField();
  const Pose2 truth(-0.5 * field.halfLength(), -field.halfWidth(), -kPi / 2);  // at the side line, facing out
  const Pose2 wrong(-1.5, 0, 0);                                                 // facing the centre circle
  PerceptGenerator gen(field, seed(77));
  gen.falseLineRate = gen.falsePointRate = 0;
  auto run = [&](const Pose2& believed, bool withView) {
    SelfLocator loc(field);
    loc.resetTo(believed, {0.05, 0.05, 0.05});
    const View view{0, 28 * kDeg, 0.5, 3.0};
    for (int i = 0; i < 60; ++i) {
      LocalizationInput in;
      FieldPercepts p = gen.perceive(truth, view, Noise{}, i * kFrameDt);
      EXPECT_TRUE(p.lines.lines.empty() && !p.lines.circle.found);  // nothing lies there
      if (withView) p.view = viewPolygon(view);
      in.percepts = {p};
      loc.update(in);
    }
    return loc;
  };
  const SelfLocator wrongWithView = run(wrong, true), wrongBlind = run(wrong, false), right = run(truth, true);
  std::printf("wrong pose: quality %.2f with the views (negative images %ld), %.2f without; true pose %.2f\n",
              wrongWithView.estimate().quality, wrongWithView.stats().negativeImages, wrongBlind.estimate().quality,
              right.estimate().quality);
  EXPECT_LT(wrongWithView.estimate().quality, 0.1);
  EXPECT_FALSE(wrongWithView.estimate().valid);
  EXPECT_EQ(wrongWithView.stats().negativeImages, 60);
  EXPECT_TRUE(wrongBlind.estimate().valid);
  EXPECT_TRUE(right.estimate().valid);
  EXPECT_EQ(right.stats().negativeImages, 0);
  // What it expected: the halfway line's run across the view and the circle's near arc.
  EXPECT_GT(wrongWithView.expectedLineLength(Eigen::Vector3d(wrong.x, wrong.y, wrong.theta), viewPolygon(View{0, 28 * kDeg, 0.5, 3.0})), 2.0);
}

TEST(ModelingTypes, OdometryDeltaAndSigmas) {
  const Pose2 a(1.0, 2.0, 0.5), step(0.3, -0.1, 0.2);
  const auto d = odometryDelta(a, a * step);
  ASSERT_TRUE(d.has_value());
  EXPECT_NEAR(d->x, step.x, 1e-12);
  EXPECT_NEAR(d->y, step.y, 1e-12);
  EXPECT_NEAR(d->theta, step.theta, 1e-12);
  EXPECT_FALSE(odometryDelta(a, Pose2(std::numeric_limits<double>::quiet_NaN(), 0, 0)).has_value());
  RobotPose p;
  p.covariance = Eigen::Vector3d(0.04, 0.01, 0.0025).asDiagonal();
  EXPECT_NEAR(p.sigmaTranslation(), 0.2, 1e-12);
  EXPECT_NEAR(p.sigmaRotation(), 0.05, 1e-12);
}

}  // namespace
}  // namespace nao
