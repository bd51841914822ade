#pragma once
// Cognition: where the ball is and where it goes. Each camera image's ball percept updates the
// stationary and rolling Kalman filters of perception/modeling/BallFilter.h, after the
// odometry between the previous image's exposure and this one's (FrameHistory). An image in
// which the modelled ball should have been seen (it projects inside the image, near enough to
// be detected) and was not counts towards "lost". docs/modeling.md.
#include <optional>

#include "perception/modeling/BallFilter.h"
#include "representations/infrastructure/FrameHistory.h"
#include "representations/modeling/BallModel.h"
#include "representations/modeling/RobotPose.h"
#include "representations/perception/CameraPercepts.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao {

template <class V>
void describe(V& v, BallFilter::Params& p) {
  v("friction", p.friction, 0.0, 10.0);
  v("stationaryProcessSigma", p.stationaryProcessSigma, 0.0, 1.0);
  v("rollingAccelSigma", p.rollingAccelSigma, 0.0, 10.0);
  v("odometryTransFraction", p.odometryTransFraction, 0.0, 1.0);
  v("odometryRotFraction", p.odometryRotFraction, 0.0, 1.0);
  v("initialVelocitySigma", p.initialVelocitySigma, 0.01, 20.0);
  v("chi2Gate", p.chi2Gate, 0.1, 1000.0);
  v("spawnChi2", p.spawnChi2, 0.1, 1000.0);
  v("minMeasurementSigma", p.minMeasurementSigma, 0.0001, 1.0);
  v("measurementInflation", p.measurementInflation, 0.01, 100.0);
  v("defaultSigmaBase", p.defaultSigmaBase, 0.001, 1.0);
  v("defaultSigmaPerMetre", p.defaultSigmaPerMetre, 0.0, 1.0);
  v("maxObservationDistance", p.maxObservationDistance, 0.5, 30.0);
  v("stationaryGrace", p.stationaryGrace, 0.0, 10.0);
  v("stationaryMaxNis", p.stationaryMaxNis, 0.1, 1000.0);
  v("nisRate", p.nisRate, 0.001, 1.0);
  v("maxHypothesesPerBank", p.maxHypothesesPerBank, 1, 100);
  v("rollingMinMeasurements", p.rollingMinMeasurements, 1, 1000);
  v("rollingSelectSpeed", p.rollingSelectSpeed, 0.0, 20.0);
  v("rollingSpeedSigmas", p.rollingSpeedSigmas, 0.0, 100.0);
  v("stopSpeed", p.stopSpeed, 0.0, 5.0);
  v("confirmPercepts", p.confirmPercepts, 1, 100);
  v("confirmWindow", p.confirmWindow, 0.0, 60.0);
  v("hypothesisTimeout", p.hypothesisTimeout, 0.01, 600.0);
  v("selectionWindow", p.selectionWindow, 0.0, 60.0);
  v("lostAfterFrames", p.lostAfterFrames, 1, 10000);
  v("lostAfterSeconds", p.lostAfterSeconds, 0.1, 3600.0);
  v("maxDt", p.maxDt, 0.01, 60.0);
  v("maxOdometryStep", p.maxOdometryStep, 0.01, 5.0);
  v("maxOdometryTurn", p.maxOdometryTurn, 0.01, 6.3);
}

namespace modules {

class BallLocator : public Module<BallLocator, Requires<CameraPercepts, FrameHistory, RobotPose>, Provides<BallModel>,
                                  Cadence::Cognition> {
 public:
  struct Params {
    BallFilter::Params filter;
    double maxExpectedDistanceTop = 4.5;     // m: farther, a missed ball is no evidence
    double maxExpectedDistanceBottom = 1.5;  // m
    double imageMargin = 0.1;                // of the image's size: a ball nearer the border may be cut
    double maxImageGap = 1.0;                // s: images farther apart: no odometry step between them
  };

  explicit BallLocator(const ModuleContext& context = {});
  const BallFilter& filter() const { return filter_; }

  // Whether a ball at `ball` (robot frame) would be inside this image and near enough to be
  // detected.
  static bool expectedInView(const Eigen::Vector2d& ball, const CameraPercepts& percepts, const Params& params);

 private:
  void update() override;

  Params params_;
  BallFilter filter_;
  std::optional<double> lastImageTime_;
  Pose2 lastOdometry_;
};

}  // namespace modules

template <class V>
void describe(V& v, modules::BallLocator::Params& p) {
  v("filter", p.filter);
  v("maxExpectedDistanceTop", p.maxExpectedDistanceTop, 0.1, 20.0);
  v("maxExpectedDistanceBottom", p.maxExpectedDistanceBottom, 0.1, 20.0);
  v("imageMargin", p.imageMargin, 0.0, 0.45);
  v("maxImageGap", p.maxImageGap, 0.01, 60.0);
}

}  // namespace nao
