#pragma once
// Option: the Autonomous Calibration Challenge's phase 1 (../shared/reference/calibration-challenge.md,
// B-Human 2021 section 3). From the start on a side line it finds which side line it stands on
// (the own goal box is to the right from the left one and to the left from the right one: that
// bearing does not depend on the uncalibrated camera's pitch, whose distorted distances once
// made the localization pick the mirrored start; the localization decides only when the box is
// not seen), walks on odometry from that known start to the side of its own goal box on
// that side (calibrationPosition; the uncalibrated localization's distances are what the camera
// offsets distort, and its validity flickers: it walked a robot off the field), then aligns itself
// with the box's short line as the top camera sees it (the line's bearing and direction do not
// depend on the camera's pitch, which the uncalibrated localization's distances do: 2.8 deg of
// top-camera pitch put the robot 26 cm off, on the front line's extension, where the box's long
// lines run edge-on), takes the box with each camera at several head pans (planViews from the
// aligned position: one body heading per pan, turned in place on odometry), has the
// Calibrator solve, applies an accepted solution, checks it on one more view and reports
// "Calibration finished" with an arm up. A solution that is not accepted gets another round of
// the rejected views at pans shifted by retakePanDeg; after maxRounds the robot reports anyway
// with the offsets it has (finishing beats being stopped at 10 min).
#include <array>
#include <string>
#include <vector>

#include "controllers/behavior/BehaviorInput.h"
#include "controllers/behavior/StateMachine.h"
#include "perception/CameraCalibration.h"
#include "perception/FieldDimensions.h"
#include "perception/calibration/CalibrationViews.h"
#include "representations/behavior/CalibrationRequest.h"
#include "representations/behavior/HeadMotionRequest.h"
#include "representations/behavior/MotionRequest.h"
#include "representations/perception/CalibrationStatus.h"
#include "representations/perception/CameraPercepts.h"

namespace nao::behavior {

class CalibrateCameras {
 public:
  struct Params {
    double settleTime = 1.0;       // s standing after the start before deciding the side
    double sideLookPitch = 0.2;    // rad: the head's pitch meanwhile (yaw 0: the box ahead to one side)
    int sideVotes = 4;             // goal box sightings that decide the side ...
    double sideShare = 0.8;        // ... when at least this share of them agree
    double sideTimeout = 4.0;      // s looking ahead; then the head looks around and the localization decides
    double turnSettle = 0.4;       // s after a turn's target is sent before its arrival counts
    double collectTimeout = 2.5;   // s per view, then the view counts as rejected
    double solveTimeout = 5.0;     // s for the calibrator to answer a solve, apply or verify
    double retakePanDeg = 7;       // the rejected views' pans move by this per round
    int maxRounds = 3;             // solve attempts before reporting what there is
    double headMaxSpeed = 1.5;     // rad/s to each view's head angles
    double alignLook = 0.8;        // s with the head on the box before the short line counts
    double alignGather = 0.6;      // s of images averaged per alignment step
    double alignDistance = 0.04;   // m: aligned when the short line's middle is this near straight ahead ...
    double alignAngle = 0.05;      // rad: ... and the line this near square to the view
    int alignSteps = 4;            // alignment walks at most; then it goes on from where it stands
    // Views from a second distance (docs/calibration/README.md, "Telling the paint from the
    // cameras"): after the planned views the robot steps back to this distance from the short
    // line and takes farPans pans (over +-45 deg) with each camera. 0: none (the Calibrator's
    // paint unknowns need them).
    double farDistance = 0;        // m
    int farPans = 3;
  };
  enum class State { Localize, GoToPosition, Align, Turn, Collect, Solve, Apply, Verify, Report, Done };

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
    int views = 0, accepted = 0, rounds = 0, alignSteps = 0;
    int side = 0;  // +1 left side line, -1 right
    std::string sideFrom;  // "goal box" or "localization"
    bool aligned = false;  // the short line was seen square ahead before the views
    bool applied = false;
    double verifyAngleDeg = -1;
  };

  CalibrateCameras(const FieldDimensions& field, const JointArray& standPosture, const Params& params);
  // A new challenge start: from the beginning.
  void restart(double time);
  Output run(const BehaviorInput& in, const CalibrationStatus& status, const CameraCalibration& current,
             const CameraPercepts& percepts);
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
  void planFrom(int sideSign, const RobotPose& pose);
  // +1 (left side line), -1 (right) or 0 (not yet) from the goal box sightings and the pose.
  int decideSide(const BehaviorInput& in, const CameraPercepts& percepts);
  void nextView(double time, Output& out);
  void startRound(double time, Output& out);
  // The odometry target that turns the body in place to a field heading.
  Pose2 turnTarget(double heading) const;
  // The odometry target of a view's field pose (planned from the anchor: a turn in place, or a
  // step back to the far views' place and a turn).
  Pose2 viewTarget(const Eigen::Vector3d& robotPose) const;
  void planViewsFromHere(const RobotPose& here, bool aligned, double time, Output& out);
  // `pose` with its field pose by the odometry since the start (the start being the rules' one).
  RobotPose byOdometry(const RobotPose& pose) const;
  // One alignment step on the top camera's percepts: the box's short line (near, ahead, square
  // to the view) gives where the calibration position is relative to the robot.
  void align(const BehaviorInput& in, const CameraPercepts& percepts, Output& out);

  FieldDimensions field_;
  JointArray stand_;
  Params params_;
  StateMachine<State> machine_{State::Localize};
  calibration::GoalBoxSide side_;
  Eigen::Vector3d position_ = Eigen::Vector3d::Zero();  // the calibration position (field)
  std::vector<PlannedView> views_;
  std::size_t current_ = 0;     // index into views_ (the check view is views_.back() in Verify)
  RobotPose anchor_;            // the pose on arrival: field headings become odometry turns
  Pose2 startPose_, startOdometry_;  // the rules' start (field) and the odometry there
  int nextViewId_ = 1;
  int walkId_ = 0;
  int solutionWanted_ = 0;
  int appliedBefore_ = 0;
  int round_ = 0;
  // Alignment: the short line's middle and direction (robot frame) summed over the gathered images.
  Eigen::Vector2d alignMiddle_ = Eigen::Vector2d::Zero(), alignDirection_ = Eigen::Vector2d::Zero();
  int alignImages_ = 0, alignStep_ = 0;
  double alignSince_ = 0;
  bool alignWalking_ = false;
  Pose2 alignTarget_;  // odometry frame
  double alignPitch_ = 0;  // rad: the head pitch of the plan's straight top view
  std::array<int, 2> sideVotes_{};  // goal box sightings to the right (left start), to the left
  double lastVoteImage_ = -1;
  Summary summary_;
};

template <class V>
void describe(V& v, CalibrateCameras::Params& p) {
  v("settleTime", p.settleTime, 0.0, 30.0);
  v("sideLookPitch", p.sideLookPitch, -0.6, 0.5);
  v("sideVotes", p.sideVotes, 1, 1000);
  v("sideShare", p.sideShare, 0.5, 1.0);
  v("sideTimeout", p.sideTimeout, 0.0, 120.0);
  v("turnSettle", p.turnSettle, 0.0, 5.0);
  v("collectTimeout", p.collectTimeout, 0.1, 30.0);
  v("solveTimeout", p.solveTimeout, 0.1, 60.0);
  v("retakePanDeg", p.retakePanDeg, 0.0, 30.0);
  v("maxRounds", p.maxRounds, 1, 10);
  v("headMaxSpeed", p.headMaxSpeed, 0.1, 10.0);
  v("alignLook", p.alignLook, 0.0, 5.0);
  v("alignGather", p.alignGather, 0.0, 5.0);
  v("alignDistance", p.alignDistance, 0.001, 1.0);
  v("alignAngle", p.alignAngle, 0.001, 1.0);
  v("alignSteps", p.alignSteps, 0, 20);
  v("farDistance", p.farDistance, 0.0, 3.0);
  v("farPans", p.farPans, 2, 9);
}

}  // namespace nao::behavior
