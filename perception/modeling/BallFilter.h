#pragma once
// Ball model: two banks of Kalman filters in the robot frame, moved by odometry. Stationary
// hypotheses estimate a 2-D position; rolling ones position and velocity (4-D) under a
// constant deceleration (the carpet's friction, a parameter to fit to the ball at hand). Each
// percept updates the best-fitting hypothesis of each bank inside a chi-square gate, or starts a
// new one. Only a hypothesis confirmed by several percepts can be the ball. The rolling hypothesis is selected once it has enough measurements and a speed
// clearly above zero; otherwise the stationary one. The ball is "lost" after a number of
// consecutive cycles in which the caller says it should have been seen and no percept fitted,
// or after some seconds unseen.
// docs/modeling.md.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "perception/modeling/ModelingTypes.h"

namespace nao {

class BallFilter {
 public:
  struct Params {
    double friction = 0.3;                // m/s^2, the constant deceleration of a rolling ball (the
                                           // simulator's, fitted by `nao-soccer train friction`)
    double stationaryProcessSigma = 0.01;  // m/sqrt(s): a lying ball's random walk
    double rollingAccelSigma = 0.15;       // m/s^2: white acceleration noise of a rolling ball
    double odometryTransFraction = 0.1;    // m of ball error per m the robot walked
    double odometryRotFraction = 0.1;      // rad of bearing error per rad the robot turned
    double initialVelocitySigma = 3.0;     // m/s, of a new rolling hypothesis
    double chi2Gate = 13.8;                // Mahalanobis^2 gate, 2 dof (99.9 %)
    double spawnChi2 = 5.99;               // a new rolling hypothesis starts when none fits this well (95 %)
    double minMeasurementSigma = 0.01;     // m: floor of a percept's standard deviation
    double measurementInflation = 1.0;     // the percepts' covariances are multiplied by this
    double defaultSigmaBase = 0.02;        // m: for a percept whose covariance is unusable ...
    double defaultSigmaPerMetre = 0.05;    // ... plus this per m of distance
    double maxObservationDistance = 12.0;  // m: farther or non-finite percepts are skipped
    double stationaryGrace = 0.1;          // s: a lying hypothesis missed for up to this long still explains the ball
    double stationaryMaxNis = 9.0;         // a lying hypothesis fitting worse than this (mean d^2) no longer explains the ball
    double nisRate = 0.15;                 // weight of the newest percept in a hypothesis' fit
    int maxHypothesesPerBank = 6;
    int rollingMinMeasurements = 4;        // before a rolling hypothesis can be selected
    double rollingSelectSpeed = 0.2;       // m/s, and faster than this ...
    double rollingSpeedSigmas = 3.5;       // ... and this many standard deviations of its speed
    double stopSpeed = 0.08;               // m/s: a slower rolling ball counts as lying
    int confirmPercepts = 3;               // fitting percepts within confirmWindow before a hypothesis
    double confirmWindow = 0.5;            // s can be the ball (a false percept now and then never is)
    double hypothesisTimeout = 2.0;        // s without a fitting percept before a hypothesis goes (a
                                           // rolling one becomes a lying one at its end position)
    double selectionWindow = 0.25;         // s: of the hypotheses seen this recently, the most measured is selected
    int lostAfterFrames = 7;               // consecutive cycles unseen while expected in view ...
    double lostAfterSeconds = 8.0;         // s ... or this long unseen wherever it was (a memory never
                                           // looked at again is no longer claimed)
    double maxDt = 1.0;                    // s: a longer gap between cycles is taken as this
    double maxOdometryStep = 0.5;          // m: a larger step is absurd and skipped
    double maxOdometryTurn = 1.0;          // rad
  };

  struct Hypothesis {
    bool rolling = false;
    Eigen::Vector4d x = Eigen::Vector4d::Zero();  // px, py, vx, vy (robot frame)
    Eigen::Matrix4d P = Eigen::Matrix4d::Identity();
    int measurements = 0;
    double lastSeen = 0;  // s
    double nis = 2;       // running mean of the normalised innovation squared (2 when it fits)
    std::vector<double> hits;  // times of its last confirmPercepts fitting percepts
    bool confirmed = false;    // once confirmPercepts of them came within confirmWindow
    std::uint64_t id = 0;
  };

  struct Stats {
    int skippedOdometry = 0;
    int skippedObservations = 0;
    int skippedTimes = 0;  // non-finite or backwards times (no prediction that cycle)
  };

  BallFilter() : BallFilter(Params()) {}
  explicit BallFilter(const Params& params);

  void reset();
  // One cognition cycle. Returns the model.
  BallModel update(const BallInput& input);
  const BallModel& model() const { return model_; }
  const std::vector<Hypothesis>& hypotheses() const { return hyps_; }
  const Stats& stats() const { return stats_; }
  const Params& params() const { return params_; }

  // The model's time (s) until the ball is closest to `target` (robot frame) on its way;
  // +infinity when it stops before, 0 when it lies (or is already past the closest point).
  double timeToReach(const Eigen::Vector2d& target) const;

  // Constant-deceleration physics (friction m/s^2 > 0; 0 means no friction).
  static Eigen::Vector2d endPosition(const Eigen::Vector2d& p, const Eigen::Vector2d& v, double friction);
  static Eigen::Vector2d positionAfter(const Eigen::Vector2d& p, const Eigen::Vector2d& v, double t, double friction);
  static Eigen::Vector2d velocityAfter(const Eigen::Vector2d& v, double t, double friction);
  // Time to cover `distance` (m) along the path from speed `speed`; +infinity if it stops first.
  static double timeToTravel(double speed, double distance, double friction);

 private:
  void applyOdometry(const Pose2& d);
  void predict(double dt);
  bool observe(const BallObservation& o, double time);
  void spawn(const Eigen::Vector2d& z, const Eigen::Matrix2d& R, bool rolling, double time);
  void prune(double time);
  void hit(Hypothesis& h, double time) const;
  void select(const BallInput& input);

  Params params_;
  std::vector<Hypothesis> hyps_;
  BallModel model_;
  std::uint64_t nextId_ = 1;
  double lastTime_ = 0;
  bool haveTime_ = false;
  Stats stats_;
};

}  // namespace nao
