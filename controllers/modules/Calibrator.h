#pragma once
// Cognition: the autonomous extrinsic calibration (B-Human 2021, section 3) inside the robot
// program. On the behaviour's CalibrationRequest it takes a sample of the goal box from the
// current image (perception/calibration: LSD segments, the goal box side, Hough-refined paint
// edges; only while the head and the torso hold still around the exposure), solves the six
// offsets by least squares over all samples, applies an accepted solution (CalibrationStatus:
// CameraCalibrationProvider in motion switches every camera matrix to it) and verifies it on a
// new view. A new challenge start (ChallengeMode::modeId) or Reset forgets everything.
#include <string>
#include <vector>

#include "perception/CameraCalibration.h"
#include "perception/calibration/Calibrator.h"
#include "perception/calibration/SampleExtraction.h"
#include "representations/behavior/CalibrationRequest.h"
#include "representations/infrastructure/ChallengeMode.h"
#include "representations/infrastructure/CurrentImage.h"
#include "representations/infrastructure/FrameHistory.h"
#include "representations/perception/CalibrationStatus.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class Calibrator : public Module<Calibrator,
                                 Requires<CurrentImage, FrameHistory, CameraCalibration, CalibrationRequest, ChallengeMode>,
                                 Provides<CalibrationStatus>, Cadence::Cognition> {
 public:
  struct Params {
    double stillSeconds = 0.15;    // the head and torso held still this long before the exposure ...
    double stillJointRad = 0.002;  // ... each head joint within this ...
    double stillImuRad = 0.003;    // ... and the torso's roll and pitch within this
    double maxOffsetDeg = 6;       // a solution with a larger offset is implausible
    int minSamplesPerCamera = 3;
    double maxRmsAngleDeg = 0.15;  // acceptance of a solution (perception/calibration/Calibrator.h)
    double maxRmsDepthM = 0.012;
    // The residuals' expected errors (perception/calibration/CalibrationCost.h): the goal box's
    // depth (the camera height the legs give, and the paint) and each right angle.
    double depthSigmaM = 0.002;
    double angleSigmaDeg = 0.02;
    // The paint as unknowns (CostOptions::paintTurns, paintDepth), with priors of the paint's
    // accuracy. Off: they need views from two distances, which the behaviour does not take yet
    // (docs/calibration/README.md, "Telling the paint from the cameras").
    bool paintTurns = false;
    bool paintDepth = false;
    double turnPriorDeg = 0.5;
    double depthPriorM = 0.01;
    std::string solver = "gauss-newton";  // or "ceres" (not in nao-soccer-robot)
    // The image's line segments: "lsd" (OpenCV's LSD), "vision" first, or "lsd+vision" (LSD, then
    // the vision's lines, then both: perception/calibration/SampleExtraction.h). lsd+vision: the
    // same as lsd on the simulator's views (eval calibration --trials 8 --seed 3: identical
    // estimates), 18 instead of 5 samples from the 39 real goal-box frames (docs/vision/real/).
    std::string lines = "lsd+vision";
    bool compareSolvers = false;          // also solve the used samples with the other solver (a check)
  };

  explicit Calibrator(const ModuleContext& context = {});
  const std::vector<calibration::CalibrationSample>& samples() const { return samples_; }

 private:
  void update() override;
  void reset();
  // The sample of this image, or the reason there is none.
  calibration::ExtractionResult extract(const CameraImage& image, const CameraCalibration& current) const;

  Params params_;
  calibration::ExtractionOptions extraction_;
  calibration::CalibratorOptions solver_;
  std::vector<calibration::CalibrationSample> samples_;
  int modeId_ = 0;
  int verifiedViewId_ = -1;
};

}  // namespace nao::modules

namespace nao {
template <class V>
void describe(V& v, modules::Calibrator::Params& p) {
  v("stillSeconds", p.stillSeconds, 0.0, 2.0);
  v("stillJointRad", p.stillJointRad, 0.0, 0.1);
  v("stillImuRad", p.stillImuRad, 0.0, 0.1);
  v("maxOffsetDeg", p.maxOffsetDeg, 0.1, 30.0);
  v("minSamplesPerCamera", p.minSamplesPerCamera, 2, 100);
  v("maxRmsAngleDeg", p.maxRmsAngleDeg, 0.001, 10.0);
  v("maxRmsDepthM", p.maxRmsDepthM, 0.0001, 1.0);
  v("depthSigmaM", p.depthSigmaM, 0.0001, 0.1);
  v("angleSigmaDeg", p.angleSigmaDeg, 0.001, 5.0);
  v("paintTurns", p.paintTurns);
  v("paintDepth", p.paintDepth);
  v("turnPriorDeg", p.turnPriorDeg, 0.001, 10.0);
  v("depthPriorM", p.depthPriorM, 0.0001, 0.1);
  v("solver", p.solver, {"gauss-newton", "ceres"});
  v("lines", p.lines, {"lsd", "vision", "lsd+vision"});
  v("compareSolvers", p.compareSolvers);
}
}  // namespace nao
