#include "perception/modeling/BallFilter.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

namespace nao {
namespace {

using Vec2 = Eigen::Vector2d;
using Vec4 = Eigen::Vector4d;
using Mat2 = Eigen::Matrix2d;
using Mat4 = Eigen::Matrix4d;
constexpr double kInf = std::numeric_limits<double>::infinity();

Mat2 rotation(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Mat2 r;
  r << c, -s, s, c;
  return r;
}

bool sane(const Mat4& P) { return P.allFinite(); }

}  // namespace

BallFilter::BallFilter(const Params& params) : params_(params) {}

void BallFilter::reset() {
  hyps_.clear();
  model_ = BallModel();
  haveTime_ = false;
}

Vec2 BallFilter::endPosition(const Vec2& p, const Vec2& v, double friction) {
  const double speed = v.norm();
  if (speed < 1e-12) return p;
  if (!(friction > 0)) return p + v * 1e3;  // no friction: "far away" along its path
  return p + v * (speed / (2 * friction));
}

Vec2 BallFilter::velocityAfter(const Vec2& v, double t, double friction) {
  const double speed = v.norm();
  if (speed < 1e-12 || !(friction > 0)) return v;
  const double s = speed - friction * std::max(0.0, t);
  return s > 0 ? Vec2(v * (s / speed)) : Vec2::Zero();
}

Vec2 BallFilter::positionAfter(const Vec2& p, const Vec2& v, double t, double friction) {
  const double speed = v.norm();
  t = std::max(0.0, t);
  if (speed < 1e-12) return p;
  if (!(friction > 0)) return p + v * t;
  const double stop = speed / friction;
  if (t >= stop) return endPosition(p, v, friction);
  return p + v * (t - friction * t * t / (2 * speed));
}

double BallFilter::timeToTravel(double speed, double distance, double friction) {
  if (distance <= 0) return 0;
  if (speed <= 1e-12) return kInf;
  if (!(friction > 0)) return distance / speed;
  const double disc = speed * speed - 2 * friction * distance;
  if (disc < 0) return kInf;
  return (speed - std::sqrt(disc)) / friction;
}

double BallFilter::timeToReach(const Vec2& target) const {
  const double speed = model_.velocity.norm();
  if (!model_.valid || speed < 1e-9) return 0;
  const Vec2 u = model_.velocity / speed;
  const double along = u.dot(target - model_.position);
  return timeToTravel(speed, along, params_.friction);
}

void BallFilter::applyOdometry(const Pose2& d) {
  if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.theta) ||
      std::hypot(d.x, d.y) > params_.maxOdometryStep || std::abs(d.theta) > params_.maxOdometryTurn) {
    ++stats_.skippedOdometry;
    return;
  }
  const Mat2 r = rotation(-d.theta);
  const Vec2 t(d.x, d.y);
  Mat4 J = Mat4::Zero();
  J.topLeftCorner<2, 2>() = r;
  J.bottomRightCorner<2, 2>() = r;
  for (auto& h : hyps_) {
    const Vec2 p = r * (h.x.head<2>() - t);
    const Vec2 v = r * h.x.tail<2>();
    h.x << p, v;
    h.P = J * h.P * J.transpose();
    const double sp = params_.odometryTransFraction * t.norm() + params_.odometryRotFraction * std::abs(d.theta) * p.norm();
    h.P(0, 0) += sp * sp;
    h.P(1, 1) += sp * sp;
  }
}

void BallFilter::predict(double dt) {
  if (dt <= 0) return;
  for (auto& h : hyps_) {
    if (!h.rolling) {
      const double q = params_.stationaryProcessSigma * params_.stationaryProcessSigma * dt;
      h.P(0, 0) += q;
      h.P(1, 1) += q;
      continue;
    }
    const Vec2 v = h.x.tail<2>();
    const double speed = v.norm();
    const double mu = params_.friction;
    double a = dt, k = 1;
    if (mu > 0 && speed > 1e-9) {
      if (speed > mu * dt) {
        a = dt - mu * dt * dt / (2 * speed);
        k = (speed - mu * dt) / speed;
      } else {
        a = speed / (2 * mu);
        k = 0;
      }
    }
    Mat4 F = Mat4::Identity();
    F(0, 2) = F(1, 3) = a;
    F(2, 2) = F(3, 3) = k;
    h.x = F * h.x;
    // Slower than a rolling ball goes: it lies (speed clipped to 0, as B-Human does).
    if (h.measurements >= params_.rollingMinMeasurements && h.x.tail<2>().norm() < params_.stopSpeed)
      h.x.tail<2>().setZero();
    const double s2 = params_.rollingAccelSigma * params_.rollingAccelSigma;
    Mat4 Q = Mat4::Zero();
    Q(0, 0) = Q(1, 1) = s2 * dt * dt * dt / 3;
    Q(0, 2) = Q(2, 0) = Q(1, 3) = Q(3, 1) = s2 * dt * dt / 2;
    Q(2, 2) = Q(3, 3) = s2 * dt;
    h.P = F * h.P * F.transpose() + Q;
  }
}

void BallFilter::spawn(const Vec2& z, const Mat2& R, bool rolling, double time) {
  Hypothesis h;
  h.rolling = rolling;
  h.x << z, 0, 0;
  h.P = Mat4::Zero();
  h.P.topLeftCorner<2, 2>() = R;
  if (rolling) {
    const double s = params_.initialVelocitySigma;
    h.P(2, 2) = h.P(3, 3) = s * s;
  }
  h.measurements = 0;
  hit(h, time);
  h.id = nextId_++;
  hyps_.push_back(h);
}

void BallFilter::hit(Hypothesis& h, double time) const {
  ++h.measurements;
  h.lastSeen = time;
  h.hits.push_back(time);
  const std::size_t n = static_cast<std::size_t>(params_.confirmPercepts);
  if (h.hits.size() > n) h.hits.erase(h.hits.begin());
  if (h.hits.size() == n && h.hits.back() - h.hits.front() <= params_.confirmWindow) h.confirmed = true;
}

bool BallFilter::observe(const BallObservation& o, double time) {
  const Vec2 z = o.position;
  if (!z.allFinite() || z.norm() > params_.maxObservationDistance) {
    ++stats_.skippedObservations;
    return false;
  }
  Mat2 R = 0.5 * (o.covariance + o.covariance.transpose()) * params_.measurementInflation;
  Eigen::SelfAdjointEigenSolver<Mat2> es;
  bool usable = R.allFinite();
  if (usable) {
    es.compute(R);
    usable = es.eigenvalues().minCoeff() > 0 && es.eigenvalues().maxCoeff() < 100;
  }
  if (!usable) {
    const double s = params_.defaultSigmaBase + params_.defaultSigmaPerMetre * z.norm();
    R = Mat2::Identity() * s * s;
  }
  const double floor2 = params_.minMeasurementSigma * params_.minMeasurementSigma;
  R(0, 0) = std::max(R(0, 0), floor2);
  R(1, 1) = std::max(R(1, 1), floor2);

  Eigen::Matrix<double, 2, 4> H = Eigen::Matrix<double, 2, 4>::Zero();
  H(0, 0) = H(1, 1) = 1;
  for (bool rolling : {false, true}) {
    // Every hypothesis of the bank inside the gate takes the percept (duplicates converge and
    // merge); a new one starts when none fits well, so that a kicked ball is picked up at once
    // by a hypothesis with an open velocity while the old one may still follow.
    double bestD2 = std::numeric_limits<double>::infinity();
    for (auto& h : hyps_) {
      if (h.rolling != rolling) continue;
      const Vec2 r = z - h.x.head<2>();
      const Mat2 S = h.P.topLeftCorner<2, 2>() + R;
      const double d2 = r.dot(S.ldlt().solve(r));
      if (!std::isfinite(d2) || d2 > params_.chi2Gate) continue;
      bestD2 = std::min(bestD2, d2);
      const Eigen::Matrix<double, 4, 2> K = h.P * H.transpose() * S.inverse();
      const Vec4 x = h.x + K * r;
      const Mat4 IKH = Mat4::Identity() - K * H;
      const Mat4 P = IKH * h.P * IKH.transpose() + K * R * K.transpose();
      if (!x.allFinite() || !sane(P)) continue;
      h.x = x;
      h.P = 0.5 * (P + P.transpose());
      hit(h, time);
      h.nis += params_.nisRate * (std::min(d2, 50.0) - h.nis);
    }
    if (bestD2 > (rolling ? params_.spawnChi2 : params_.chi2Gate)) spawn(z, R, rolling, time);
  }
  return true;
}

void BallFilter::prune(double time) {
  // Merge hypotheses of a bank that became the same.
  for (std::size_t i = 0; i < hyps_.size(); ++i)
    for (std::size_t j = i + 1; j < hyps_.size();) {
      const Hypothesis &a = hyps_[i], &b = hyps_[j];
      const bool same = a.rolling == b.rolling && (a.x.head<2>() - b.x.head<2>()).norm() < 0.05 &&
                        (a.x.tail<2>() - b.x.tail<2>()).norm() < 0.2;
      if (same) {
        if (b.measurements > a.measurements) std::swap(hyps_[i], hyps_[j]);
        hyps_[i].lastSeen = std::max(hyps_[i].lastSeen, hyps_[j].lastSeen);
        hyps_[i].confirmed = hyps_[i].confirmed || hyps_[j].confirmed;
        hyps_.erase(hyps_.begin() + static_cast<std::ptrdiff_t>(j));
      } else {
        ++j;
      }
    }
  // A rolling hypothesis unseen for hypothesisTimeout has stopped by now (or never rolled): it
  // lies at its end position (its open velocity would otherwise let it take any percept).
  for (auto& h : hyps_)
    if (h.rolling && time - h.lastSeen > params_.hypothesisTimeout) {
      h.rolling = false;
      h.x.head<2>() = endPosition(h.x.head<2>(), h.x.tail<2>(), params_.friction);
      h.x.tail<2>().setZero();
      const Mat2 position = h.P.topLeftCorner<2, 2>();
      h.P.setZero();
      h.P.topLeftCorner<2, 2>() = position;
    }
  // Forget stale ones, but keep the newest confirmed one as the memory of the ball (an
  // unconfirmed one is forgotten when stale: it never was the ball).
  double newest = -kInf;
  for (const auto& h : hyps_)
    if (h.confirmed) newest = std::max(newest, h.lastSeen);
  hyps_.erase(std::remove_if(hyps_.begin(), hyps_.end(),
                             [&](const Hypothesis& h) {
                               return !h.x.allFinite() || !sane(h.P) ||
                                      (time - h.lastSeen > params_.hypothesisTimeout &&
                                       (!h.confirmed || h.lastSeen < newest));
                             }),
              hyps_.end());
  // At most maxHypothesesPerBank per bank: the confirmed ones, then the most recently seen, then
  // the most measured (a burst of false percepts does not push the ball out).
  std::stable_sort(hyps_.begin(), hyps_.end(), [](const Hypothesis& a, const Hypothesis& b) {
    if (a.confirmed != b.confirmed) return a.confirmed;
    if (a.lastSeen != b.lastSeen) return a.lastSeen > b.lastSeen;
    return a.measurements > b.measurements;
  });
  int stationary = 0, rolling = 0;
  hyps_.erase(std::remove_if(hyps_.begin(), hyps_.end(),
                             [&](const Hypothesis& h) {
                               int& n = h.rolling ? rolling : stationary;
                               return ++n > params_.maxHypothesesPerBank;
                             }),
              hyps_.end());
}

void BallFilter::select(const BallInput& input) {
  // The lying ball: of the stationary hypotheses seen in the last selectionWindow, the most
  // measured (one percept outside the gate does not move the model). The rolling ball: of the
  // rolling ones seen in that window with enough measurements and a speed clearly above zero,
  // the most measured; it is selected when the lying one no longer explains the percepts.
  double newest = -std::numeric_limits<double>::infinity();
  for (const auto& h : hyps_)
    if (h.confirmed) newest = std::max(newest, h.lastSeen);
  const double since = newest - params_.selectionWindow;
  auto better = [](const Hypothesis* a, const Hypothesis& h) {
    return !a || h.measurements > a->measurements || (h.measurements == a->measurements && h.lastSeen > a->lastSeen);
  };
  auto moving = [&](const Hypothesis& h) {
    const Vec2 v = h.x.tail<2>();
    const double speed = v.norm();
    if (speed < params_.rollingSelectSpeed) return false;
    const Vec2 u = v / speed;
    const double var = u.dot(h.P.bottomRightCorner<2, 2>() * u);
    return speed > params_.rollingSpeedSigmas * std::sqrt(std::max(0.0, var));
  };
  const Hypothesis* st = nullptr;
  const Hypothesis* ro = nullptr;
  for (const auto& h : hyps_) {
    if (h.lastSeen < since || !h.confirmed) continue;
    if (!h.rolling && better(st, h)) st = &h;
    if (h.rolling && h.measurements >= params_.rollingMinMeasurements && moving(h) && better(ro, h)) ro = &h;
  }
  // A lying ball that still explains the percepts keeps the model lying: a rolling hypothesis
  // born of a false percept beside the ball shows a speed too.
  const bool stationaryFits = st && st->lastSeen >= newest - params_.stationaryGrace &&
                              st->nis <= params_.stationaryMaxNis &&
                              (!ro || st->measurements >= ro->measurements);
  const bool useRolling = ro != nullptr && !stationaryFits;
  const Hypothesis* sel = useRolling ? ro : st;
  if (!sel)  // the memory: the most recently seen confirmed hypothesis (a rolling one with its measurements)
    for (const auto& h : hyps_)
      if (h.confirmed && (!h.rolling || h.measurements >= params_.rollingMinMeasurements) &&
          (!sel || h.lastSeen > sel->lastSeen))
        sel = &h;
  if (!sel) {
    model_.valid = false;
    model_.fieldValid = false;
    return;
  }
  model_.valid = true;
  model_.seenTime = sel->lastSeen;
  model_.rolling = sel->rolling && useRolling;
  model_.position = sel->x.head<2>();
  model_.velocity = model_.rolling ? Vec2(sel->x.tail<2>()) : Vec2::Zero();
  model_.covariance = sel->P;
  if (!model_.rolling) {
    model_.covariance.topRightCorner<2, 2>().setZero();
    model_.covariance.bottomLeftCorner<2, 2>().setZero();
    model_.covariance.bottomRightCorner<2, 2>().setZero();
  }
  model_.endPosition = endPosition(model_.position, model_.velocity, params_.friction);
  const auto& rp = input.robotPose;
  model_.fieldValid = rp && std::isfinite(rp->x) && std::isfinite(rp->y) && std::isfinite(rp->theta);
  if (model_.fieldValid) {
    model_.fieldPosition = (*rp) * model_.position;
    model_.fieldEndPosition = (*rp) * model_.endPosition;
    model_.fieldVelocity = rotation(rp->theta) * model_.velocity;
  }
}

BallModel BallFilter::update(const BallInput& input) {
  double dt = 0;
  double time = lastTime_;
  if (!std::isfinite(input.time) || (haveTime_ && input.time < lastTime_)) {
    ++stats_.skippedTimes;
  } else {
    time = input.time;
    if (haveTime_) dt = std::min(params_.maxDt, time - lastTime_);
    lastTime_ = time;
    haveTime_ = true;
  }
  applyOdometry(input.odometryDelta);
  predict(dt);
  for (const auto& o : input.observations) observe(o, time);
  prune(time);
  const bool wasValid = model_.valid;
  select(input);
  // Seen: a percept fitted the hypothesis that is the ball (not merely any percept: a false
  // one elsewhere neither refreshes the ball nor keeps it from being lost).
  if (model_.valid && model_.seenTime >= time) {
    model_.unseenFrames = 0;
    model_.lost = false;
  } else if (input.ballExpectedInView && wasValid) {
    ++model_.unseenFrames;
    if (model_.unseenFrames >= params_.lostAfterFrames) model_.lost = true;
  }
  if (model_.valid && time - model_.seenTime > params_.lostAfterSeconds) model_.lost = true;
  return model_;
}

}  // namespace nao
