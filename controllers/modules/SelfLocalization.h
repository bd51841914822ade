#pragma once
// Cognition: where the robot is. Each camera image's percepts (CameraPercepts) move the
// multi-hypothesis filter of perception/modeling/SelfLocator.h, after the odometry between the
// previous image's exposure and this one's (FrameHistory, interpolated to the image times).
// The field's symmetry comes from the game situation (GameState): hypotheses start at the own
// half's side lines, and a robot whose penalty ends returns at the side lines level with its
// own penalty mark. docs/modeling.md.
#include <optional>

#include "perception/modeling/SelfLocator.h"
#include "representations/infrastructure/FrameHistory.h"
#include "representations/infrastructure/GameState.h"
#include "representations/infrastructure/ChallengeMode.h"
#include "representations/modeling/RobotPose.h"
#include "representations/perception/CameraPercepts.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao {

template <class V>
void describe(V& v, PerceptUncertainty& p) {
  v("sigmaBase", p.sigmaBase, 0.001, 1.0);
  v("sigmaPerMetre", p.sigmaPerMetre, 0.0, 1.0);
  v("sigmaAngle", p.sigmaAngle, 0.001, 1.0);
  v("sigmaAnglePerMetre", p.sigmaAnglePerMetre, 0.0, 1.0);
}

template <class V>
void describe(V& v, SelfLocator::Params& p) {
  v("odomTransPerMetre", p.odomTransPerMetre, 0.0, 2.0);
  v("odomTransPerRad", p.odomTransPerRad, 0.0, 2.0);
  v("odomRotPerRad", p.odomRotPerRad, 0.0, 2.0);
  v("odomRotPerMetre", p.odomRotPerMetre, 0.0, 2.0);
  v("odomTransFloor", p.odomTransFloor, 0.0, 0.1);
  v("odomRotFloor", p.odomRotFloor, 0.0, 0.1);
  v("maxOdometryStep", p.maxOdometryStep, 0.01, 5.0);
  v("maxOdometryTurn", p.maxOdometryTurn, 0.01, 6.3);
  v("lineGate", p.lineGate, 0.01, 5.0);
  v("lineAngleGate", p.lineAngleGate, 0.01, 1.6);
  v("maxAngleWidening", p.maxAngleWidening, 0.0, 1.6);
  v("lineEndMargin", p.lineEndMargin, 0.0, 5.0);
  v("minLineLength", p.minLineLength, 0.0, 5.0);
  v("intersectionGate", p.intersectionGate, 0.01, 5.0);
  v("circleGate", p.circleGate, 0.01, 5.0);
  v("penaltyMarkGate", p.penaltyMarkGate, 0.01, 5.0);
  v("chi2Gate", p.chi2Gate, 0.1, 1000.0);
  v("maxPerceptDistance", p.maxPerceptDistance, 0.5, 20.0);
  v("negativeMinExpected", p.negativeMinExpected, 0.0, 100.0);
  v("negativeDetectRate", p.negativeDetectRate, 0.0, 1.0);
  v("negativeMinArc", p.negativeMinArc, 0.0, 10.0);
  v("negativeMissedCircle", p.negativeMissedCircle, 0.0, 1.0);
  v("maxHypotheses", p.maxHypotheses, 1, 100);
  v("scoreRate", p.scoreRate, 0.001, 1.0);
  v("mergeDistance", p.mergeDistance, 0.0, 5.0);
  v("mergeAngle", p.mergeAngle, 0.0, 3.2);
  v("pruneMargin", p.pruneMargin, 0.0, 1.0);
  v("pruneMinAge", p.pruneMinAge, 0, 100000);
  v("switchMargin", p.switchMargin, 0.0, 1.0);
  v("clusterDistance", p.clusterDistance, 0.01, 5.0);
  v("clusterAngle", p.clusterAngle, 0.01, 3.2);
  v("clusterLifetime", p.clusterLifetime, 0.1, 600.0);
  v("maxClusters", p.maxClusters, 1, 100);
  v("clusterMinObservations", p.clusterMinObservations, 1, 1000);
  v("resetDistance", p.resetDistance, 0.0, 20.0);
  v("resetAngle", p.resetAngle, 0.0, 3.2);
  v("resetScore", p.resetScore, 0.0, 1.0);
  v("candidateMinSupport", p.candidateMinSupport, 0.0, 1.0);
  v("candidateMinPercepts", p.candidateMinPercepts, 1, 100);
  v("maxGyroForFeatures", p.maxGyroForFeatures, 0.0, 20.0);
  v("mirrorAngleWeight", p.mirrorAngleWeight, 0.0, 100.0);
  v("validQuality", p.validQuality, 0.0, 1.0);
  v("validSigmaTranslation", p.validSigmaTranslation, 0.0, 20.0);
  v("validSigmaRotation", p.validSigmaRotation, 0.0, 3.2);
  v("situationPriorImages", p.situationPriorImages, 0, 100000);
  v("situationPriorMargin", p.situationPriorMargin, 0.0, 5.0);
  v("situationMirrorDistance", p.situationMirrorDistance, 0.0, 20.0);
  v("situationMirrorAngle", p.situationMirrorAngle, 0.0, 3.2);
  v("offFieldMargin", p.offFieldMargin, 0.0, 10.0);
  v("sidelineSigmaX", p.sidelineSigma[0], 0.001, 10.0);
  v("sidelineSigmaY", p.sidelineSigma[1], 0.001, 10.0);
  v("sidelineSigmaTheta", p.sidelineSigma[2], 0.001, 3.2);
  v("penaltyReturnSigmaX", p.penaltyReturnSigma[0], 0.001, 10.0);
  v("penaltyReturnSigmaY", p.penaltyReturnSigma[1], 0.001, 10.0);
  v("penaltyReturnSigmaTheta", p.penaltyReturnSigma[2], 0.001, 3.2);
}

namespace modules {

class SelfLocalization
    : public Module<SelfLocalization, Requires<CameraPercepts, FrameHistory, GameState, ChallengeMode>, Provides<RobotPose>,
                    Cadence::Cognition> {
 public:
  struct Params {
    SelfLocator::Params filter;
    PerceptUncertainty top{0.03, 0.04, 0.04, 0.01};     // the top camera's percepts
    PerceptUncertainty bottom{0.02, 0.03, 0.03, 0.01};  // the bottom camera's: closer, sharper
    double maxImageGap = 1.0;  // s: images farther apart than this are taken as a restart
    // The ground each camera surely shows lines on (negative information, ViewRegion.h): the
    // image less this margin, to this distance.
    double viewMargin = 0.1;            // of the image's width and height, each side
    double viewDistanceTop = 3.0;       // m
    double viewDistanceBottom = 2.0;    // m
  };

  // The field: context.params["FieldDimensions"] (the run's field file), else
  // field_dimensions.json in the configuration folder.
  explicit SelfLocalization(const ModuleContext& context = {});
  const SelfLocator& locator() const { return locator_; }
  long skippedImages() const { return skippedImages_; }
  long skippedOdometry() const { return skippedOdometry_; }

 private:
  void update() override;
  void applySituation(const GameState& game, const ChallengeMode& challenge);

  Params params_;
  SelfLocator locator_;
  std::optional<double> lastImageTime_;
  Pose2 lastOdometry_;
  bool started_ = false;
  bool wasPenalised_ = false;
  gc::State lastGameState_ = gc::State::Initial;
  int challengeModeId_ = 0;  // the last challenge start, which placed the robot at its start
  long skippedImages_ = 0;    // without a usable time or odometry history
  long skippedOdometry_ = 0;  // with a non-finite odometry reading at the image's time
};

}  // namespace modules

template <class V>
void describe(V& v, modules::SelfLocalization::Params& p) {
  v("filter", p.filter);
  v("top", p.top);
  v("bottom", p.bottom);
  v("maxImageGap", p.maxImageGap, 0.01, 60.0);
  v("viewMargin", p.viewMargin, 0.0, 0.45);
  v("viewDistanceTop", p.viewDistanceTop, 0.0, 20.0);
  v("viewDistanceBottom", p.viewDistanceBottom, 0.0, 20.0);
}

}  // namespace nao
