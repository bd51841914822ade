#pragma once
// Option: where the head looks. A known ball is tracked (with a glance at the field now and
// then when the pose grows uncertain; while the pose is not valid, only a near ball); otherwise the head looks at the field feature that would
// shrink the pose covariance most (an information-gain choice over the field's intersections,
// centre circle, penalty marks and points along the lines, within the head's reach and the
// cameras' useful range); with no valid pose it sweeps. Head speed is limited so that images
// taken while it moves stay sharp enough for the vision.
#include <vector>

#include <Eigen/Core>

#include "controllers/behavior/BehaviorInput.h"
#include "controllers/behavior/StateMachine.h"
#include "perception/FieldDimensions.h"
#include "representations/behavior/HeadMotionRequest.h"

namespace nao::behavior {

class LookActive {
 public:
  struct Params {
    double maxHeadSpeed = 1.5;        // rad/s: the vision's motion-blur budget at 30 Hz
    double dwell = 1.2;               // s on one feature before choosing the next
    double minDistance = 0.5;         // m: features nearer are below the top camera's view
    double maxDistance = 4.5;         // m: farther ones are too small to help
    double maxYaw = 1.6;              // rad: feature bearings the head may turn to
    double yawCost = 0.15;            // information (nats) per rad of head turn: prefer near views
    double sigmaBase = 0.03;          // m: a feature's measurement noise ...
    double sigmaPerMetre = 0.04;      // ... growing with the distance
    double lineSampleSpacing = 1.0;   // m between points sampled along each line
    double ballRecent = 2.0;          // s: a ball seen this recently is tracked ...
    double ballNearWhileLost = 1.5;   // m: ... and, while the pose is not valid, only one this near
    double bottomCameraDistance = 1.2;  // m: nearer balls are looked at with the bottom camera
    double glanceSigma = 0.15;        // m: while tracking the ball, glance at the field above this ...
    double glanceEvery = 4.0;         // s ...
    double glanceFor = 1.2;           // s
    double sweepAmplitude = 1.4;      // rad
    double sweepPitch = 0.3;          // rad (down)
    double sweepSpeed = 1.2;          // rad/s
  };
  enum class State { Sweep, LookAtFeature, TrackBall, Glance };

  // A point that a view of would inform the pose: a point feature (both directions) or a point
  // on a line (only across it).
  struct Feature {
    Eigen::Vector2d position;
    bool onLine = false;
    Eigen::Vector2d normal = Eigen::Vector2d::Zero();  // onLine: unit normal of the line
  };

  explicit LookActive(const FieldModel& field) : LookActive(field, Params()) {}
  LookActive(const FieldModel& field, const Params& params);
  void run(const BehaviorInput& in, HeadMotionRequest& request);
  State state() const { return machine_.state; }
  const std::vector<Feature>& features() const { return features_; }

  // The expected information gain (nats: half the log-ratio of the covariance's determinants)
  // of seeing `feature` from `pose` with pose covariance `cov`; 0 when out of range or reach.
  double informationGain(const Feature& feature, const Pose2& pose, const Eigen::Matrix3d& cov) const;
  // The index of the best feature to look at (information gain less the cost of turning the
  // head there from currentYaw), skipping `skip`; -1 when none is in reach.
  int choose(const Pose2& pose, const Eigen::Matrix3d& cov, double currentYaw, int skip = -1) const;
  int target() const { return target_; }

 private:
  void lookAt(const Eigen::Vector2d& field, const Pose2& pose, HeadMotionRequest& request) const;

  Params params_;
  std::vector<Feature> features_;
  StateMachine<State> machine_{State::Sweep};
  int target_ = -1;  // index into features_
  double targetSince_ = -1e9;
  double lastGlance_ = -1e9;
};

template <class V>
void describe(V& v, LookActive::Params& p) {
  v("maxHeadSpeed", p.maxHeadSpeed, 0.1, 8.0);
  v("dwell", p.dwell, 0.1, 30.0);
  v("minDistance", p.minDistance, 0.0, 10.0);
  v("maxDistance", p.maxDistance, 0.1, 20.0);
  v("maxYaw", p.maxYaw, 0.0, 2.09);
  v("yawCost", p.yawCost, 0.0, 10.0);
  v("sigmaBase", p.sigmaBase, 0.001, 1.0);
  v("sigmaPerMetre", p.sigmaPerMetre, 0.0, 1.0);
  v("lineSampleSpacing", p.lineSampleSpacing, 0.1, 10.0);
  v("ballRecent", p.ballRecent, 0.0, 60.0);
  v("ballNearWhileLost", p.ballNearWhileLost, 0.0, 20.0);
  v("bottomCameraDistance", p.bottomCameraDistance, 0.0, 10.0);
  v("glanceSigma", p.glanceSigma, 0.0, 10.0);
  v("glanceEvery", p.glanceEvery, 0.1, 600.0);
  v("glanceFor", p.glanceFor, 0.1, 60.0);
  v("sweepAmplitude", p.sweepAmplitude, 0.05, 2.09);
  v("sweepPitch", p.sweepPitch, -0.6, 0.5);
  v("sweepSpeed", p.sweepSpeed, 0.05, 8.0);
}

}  // namespace nao::behavior
