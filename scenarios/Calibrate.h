#pragma once
// The autonomous extrinsic camera calibration in the simulator, done by the robot program and
// scored against the injected truth: the calibration challenge's phase 1
// (../shared/reference/calibration-challenge.md). The referee places the robot at the start (a
// side line, in line with the own penalty mark), holds the camera shield over it, takes the
// shield away and holds chest + head front; the robot program localizes, walks to the side of
// its own goal box, turns for each view, takes the samples (its Calibrator module), solves,
// applies, verifies and reports "Calibration finished" with an arm up. Nothing moves the robot
// after the placement; the scorer reads the truth (the injected offsets, the true camera poses
// for the reprojection, the path the robot walked).
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "controllers/modules/Calibrator.h"
#include "perception/CameraCalibration.h"
#include "perception/FieldDimensions.h"
#include "perception/calibration/Calibrator.h"
#include "perception/calibration/CalibrationViews.h"
#include "perception/calibration/SampleExtraction.h"
#include "robot/CameraImage.h"
#include "robot/JointIds.h"
#include "robot/Debug.h"
#include "scenarios/ChallengeReferee.h"
#include "sim/Lighting.h"
#include "sim/VenueLook.h"

namespace nao::sim {

struct CalibrationRunOptions {
  FieldDimensions field;
  std::string robotModel;                 // empty: models/nao_v6.xml
  CameraCalibration miscalibration;       // injected into the simulated hardware
  Lighting lighting;
  int side = -1;                          // start on the right (-1, y < 0) or left (+1) side line
  // The robot program's Calibrator parameters (config/parameters/Calibrator.json unless set):
  // calibrate's --solver, --lines and --compare go here.
  std::optional<modules::Calibrator::Params> calibrator;
  std::uint64_t seed = 1;
  std::string imagesDir;                  // non-empty: every view annotated, and the Fig. 2 pictures
  std::string recordPath;                 // non-empty: the calibration log written here (controllers/CalibrationLogging.h)
  double shieldSeconds = 2;               // the camera shield before the start (dark frames)
  double timeLimit = 600;                 // s of the phase (the rules' 10 min)
  bool randomize = false;                 // a foreign robot (ChallengeSetup::randomize)
  std::optional<double> floorFriction;    // the venue's carpet
  VenueLook venue;                        // how the venue looks (sim/VenueLook.h)
  std::optional<std::array<Eigen::Vector2d, 2>> balls;  // phase 1's balls (else near the halves' centres, from seed)
  std::function<void(double simTime)> progress;  // about once per simulated second
  DebugChannels* debug = nullptr;         // the robot program's debug channels (not owned); null: none
};

struct ViewRecord {
  CameraId camera = CameraId::Top;
  double headYawDeg = 0, headPitchDeg = 0;
  bool accepted = false;
  std::string reason;                     // why rejected
  std::optional<calibration::SampleResiduals> residuals;  // at the estimate, when used in the solve
  double extractMs = 0;                   // wall time from image to sample (or rejection)
  std::string source;                     // where the sample's segments came from: vision or lsd
  Eigen::Vector3d truePose = Eigen::Vector3d::Zero();  // where the robot stood (truth: x, y, theta)
};

// A moment the referee noted (the buttons, what the robot said); t from the phase's start.
using CalibrationEvent = ChallengeEvent;

struct CalibrationRunResult {
  std::string headId;                     // the simulated robot's head id (the calibration store's key)
  CameraCalibration truth;
  CameraCalibration estimate;             // what the robot applied (none applied: its last solution)
  bool applied = false;
  calibration::CalibrationSolution solution;  // the robot's last solve
  std::optional<calibration::SolverResult> otherSolver;  // Calibrator.compareSolvers: the other solver, same samples
  double verifyAngleDeg = -1;             // the robot's own check of the applied offsets
  std::vector<ViewRecord> views;          // every view the robot's calibrator judged, in order
  int samples = 0;
  // Field lines in every accepted view: RMS pixel distance between where the camera model
  // puts them (with the estimate / with no offsets, at the true robot pose) and where they
  // truly are in the image (the simulator's camera pose).
  double reprojectionPx = 0, reprojectionBeforePx = 0;
  int reprojectionPoints = 0;
  // The phase as the referee saw it: from the start signal (the button hold reaching 1 s) to
  // the report ("Calibration finished" said with an arm up, in truth).
  bool finished = false;
  double phaseSeconds = 0;
  double pathLength = 0, maxStep = 0;     // m walked (truth), the largest move in one 12 ms cycle
  bool fell = false;                      // the referee saw a fall (ChallengeReferee)
  std::string terminated;                 // the referee's termination reason ("" none; phase_time: no report in time)
  std::vector<CalibrationEvent> events;
  double wallSeconds = 0;
  std::vector<std::string> imagesWritten;
  // The accepted views' images and what the robot knew at their exposure (bench calibration
  // extracts their samples again to time the library).
  struct Capture {
    CameraImage image;
    JointArray joints{};
    Eigen::Vector2d imuAngle = Eigen::Vector2d::Zero();
  };
  std::vector<Capture> accepted;
};

class World;
class ChallengeSession;
// The camera shield the referee holds over the robot: a dark frame (YUYV black) in place of a render.
CameraImage shieldFrame(const World& world, CameraId camera, double time);

// Phase 1 of the challenge by the robot program. Not finished within the time limit: the
// result says so (finished false) with whatever the robot had done.
CalibrationRunResult runCalibration(const CalibrationRunOptions& options);
// The same on a session the caller keeps (the challenge goes on to phase 2 with it).
void runCalibrationPhase(ChallengeSession& session, const CalibrationRunOptions& options, CalibrationRunResult& result);
// The session a calibration run's options describe.
struct ChallengeSetup;
ChallengeSetup challengeSetup(const CalibrationRunOptions& options);
// Phase 1's balls: roughly in the centre of each half (own first), from the seed.
std::array<Eigen::Vector2d, 2> phaseOneBalls(const FieldDimensions& field, std::uint64_t seed);

struct CalibrationEvalOptions {
  int trials = 100;
  std::uint64_t seed = 1;
  FieldDimensions field;
  std::string robotModel;
  std::vector<Lighting> lightings;        // one is drawn per trial
  double maxOffsetDeg = 3;                // injected offsets uniform in +-this, per parameter
  calibration::SolverKind solver = calibration::SolverKind::GaussNewton;
  bool compareSolvers = true;             // the robot's calibrator checks its solve with the other solver
  double timeLimit = 600;                 // s of each trial's phase
  VenueChoice venue;                      // the look of trial seed s: venue.forSeed(s)
  bool randomize = false;                 // foreign robots (ChallengeSetup::randomize)
  std::string imagesDir;                  // non-empty: trial seed s writes its views into imagesDir/seed_s
  std::function<void(int done, int total)> progress;
  DebugChannels* debug = nullptr;         // every trial's robot program's debug channels (not owned)
};

struct CalibrationTrial {
  CalibrationRunResult run;
  std::string lighting;
  std::string venue;  // the look's name
  int side = -1;
};

struct CalibrationEvalResult {
  int trials = 0, converged = 0, accepted = 0, finished = 0;
  std::array<double, 6> medianAbsErrorDeg{}, p95AbsErrorDeg{}, maxAbsErrorDeg{};
  double reprojectionMedianPx = 0, reprojectionP95Px = 0, reprojectionMaxPx = 0;
  double solverAgreementMaxDeg = 0;        // largest |GN - Ceres| over all trials and parameters
  double solveSecondsMax = 0, otherSolveSecondsMax = 0, solveSecondsMedian = 0;
  double phaseSecondsMedian = 0, phaseSecondsMax = 0;
  std::vector<CalibrationTrial> trialResults;
};

// One trial, everything drawn from `seed` (offsets, lighting, start side, look, the robot):
// trial t of evalCalibration is seed options.seed + t, so rows of other runs combine.
CalibrationTrial runCalibrationTrial(const CalibrationEvalOptions& options, std::uint64_t seed);
CalibrationEvalResult evalCalibration(const CalibrationEvalOptions& options);

// Quantile q (0..1) by nearest rank of the sorted values; 0 for none.
double quantile(std::vector<double> values, double q);

}  // namespace nao::sim
