#pragma once
// Option: the Autonomous Calibration Challenge's phase 1 (../shared/reference/calibration-challenge.md,
// B-Human 2021 section 3). From the start on a side line it localizes (the start's two poses),
// walks to the side of its own goal box on that side (calibrationPosition), takes the box with
// each camera at several head pans (planViews: one body heading per pan, turned in place on
// odometry, so the miscalibrated localization only has to bring it near the spot), has the
// Calibrator solve, applies an accepted solution, checks it on one more view and reports
// "Calibration finished" with an arm up. A solution that is not accepted gets another round of
// the rejected views at pans shifted by retakePanDeg; after maxRounds the robot reports anyway
// with the offsets it has (finishing beats being stopped at 10 min).
#include <string>
#include <vector>

#include "controllers/behavior/BehaviorInput.h"
#include "controllers/behavior/GoToPose.h"
#include "controllers/behavior/StateMachine.h"
#include "perception/CameraCalibration.h"
#include "perception/FieldDimensions.h"
#include "perception/calibration/CalibrationViews.h"
#include "representations/behavior/CalibrationRequest.h"
#include "representations/behavior/HeadMotionRequest.h"
#include "representations/behavior/MotionRequest.h"
#include "representations/perception/CalibrationStatus.h"

namespace nao::behavior {

class CalibrateCameras {
 public:
  struct Params {
    double settleTime = 1.0;       // s standing after the start before trusting the localization
    double turnSettle = 0.4;       // s after a turn's target is sent before its arrival counts
    double collectTimeout = 2.5;   // s per view, then the view counts as rejected
    double solveTimeout = 5.0;     // s for the calibrator to answer a solve, apply or verify
    double retakePanDeg = 7;       // the rejected views' pans move by this per round
    int maxRounds = 3;             // solve attempts before reporting what there is
    double verifyMaxDeg = 0.1;     // the check view's largest angle residual at the applied offsets
    double headMaxSpeed = 1.5;     // rad/s to each view's head angles
    double arrivedDistance = 0.1;  // m: the calibration position by the estimate ...
    double arrivedAngle = 0.1;     // rad
  };
  enum class State { Localize, GoToPosition, Turn, Aim, Collect, Solve, Apply, Verify, Report, Done };

  // What it asks for. `lookActive` while localizing and walking (the caller's LookActive
  // chooses the head then); `report` once, with the text to say.
  struct Output {
    MotionRequest motion;
    HeadMotionRequest head;
    bool lookActive = true;
    CalibrationRequest calibration;
    std::string report;  // non-empty: start this report now
  };
  // The result, for the log and the referee's pictures.
  struct Summary {
    int views = 0, accepted = 0, rounds = 0;
    bool applied = false;
    double verifyAngleDeg = -1;
  };

  CalibrateCameras(const FieldDimensions& field, const JointArray& standPosture, const Params& params);
  // A new challenge start: from the beginning.
  void restart(double time);
  Output run(const BehaviorInput& in, const CalibrationStatus& status, const CameraCalibration& current);
  State state() const { return machine_.state; }
  // The report is over: stand still from now on.
  void reported(double time) {
    if (machine_.state == State::Report) machine_.go(State::Done, time);
  }
  bool done() const { return machine_.state == State::Done; }
  const Summary& summary() const { return summary_; }

 private:
  struct PlannedView {
    calibration::CalibrationView view;
    int viewId = 0;
    bool taken = false;  // a sample was accepted
  };
  void planFrom(const RobotPose& pose);
  void nextView(double time, Output& out);
  void startRound(double time, Output& out);
  // The odometry target that turns the body in place to a field heading.
  Pose2 turnTarget(double heading) const;

  FieldDimensions field_;
  JointArray stand_;
  Params params_;
  StateMachine<State> machine_{State::Localize};
  calibration::GoalBoxSide side_;
  Eigen::Vector3d position_ = Eigen::Vector3d::Zero();  // the calibration position (field)
  std::vector<PlannedView> views_;
  std::size_t current_ = 0;     // index into views_ (the check view is views_.back() in Verify)
  RobotPose anchor_;            // the estimate on arrival: field headings become odometry turns
  int nextViewId_ = 1;
  int walkId_ = 0;
  int solutionWanted_ = 0;
  int appliedBefore_ = 0;
  int round_ = 0;
  GoToPose goTo_;
  Summary summary_;
};

template <class V>
void describe(V& v, CalibrateCameras::Params& p) {
  v("settleTime", p.settleTime, 0.0, 30.0);
  v("turnSettle", p.turnSettle, 0.0, 5.0);
  v("collectTimeout", p.collectTimeout, 0.1, 30.0);
  v("solveTimeout", p.solveTimeout, 0.1, 60.0);
  v("retakePanDeg", p.retakePanDeg, 0.0, 30.0);
  v("maxRounds", p.maxRounds, 1, 10);
  v("verifyMaxDeg", p.verifyMaxDeg, 0.001, 10.0);
  v("headMaxSpeed", p.headMaxSpeed, 0.1, 10.0);
  v("arrivedDistance", p.arrivedDistance, 0.01, 1.0);
  v("arrivedAngle", p.arrivedAngle, 0.01, 1.0);
}

}  // namespace nao::behavior
