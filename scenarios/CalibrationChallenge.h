#pragma once
// The Autonomous Calibration Challenge, headless (../shared/reference/calibration-challenge.md):
// phase 1 (the robot program calibrates itself, scenarios/Calibrate.h) and phase 2 (five
// tasks: the ball in each half reported, three spots walked to), with the referee's placement,
// shield, buttons and taps, its termination rules and its scoring: the error of each report
// against the truth, exact and rounded to 10 cm, the phases' times, exact and rounded to 5 s.
// The same robot program plays both phases; nothing moves it but the referee's placements.
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "scenarios/Calibrate.h"
#include "scenarios/ChallengeSession.h"

namespace nao::sim {

struct ChallengeOptions {
  CalibrationRunOptions run;         // the robot, venue, offsets, lighting, start, seed, images, debug
  bool skipCalibration = false;      // phase 2 with the factory calibration (no phase 1)
  std::optional<std::array<Eigen::Vector2d, 2>> phaseTwoBalls;  // else drawn from the seed
  std::string venue;                 // the venue's name for the JSON ("" none: balls from the seed)
  double tapPause = 2.0;             // s from a report to the referee's tap (the clock is paused)
  std::function<void(int phase, double simTime)> progress;  // about once per simulated second of a phase
  double placePause = 2.5;           // s from phase 1's report to the placement for phase 2 (the report's arm comes down)
};

struct ChallengeTaskResult {
  std::string task;                  // ball_own, walk_own_goal, walk_center, ball_opponent, walk_opponent_goal
  std::string said;                  // the report's sentence ("" none)
  std::optional<Eigen::Vector2d> reported;  // field m: the ball said, or where the robot stood at the report
  Eigen::Vector2d truth = Eigen::Vector2d::Zero();  // the ball, or the spot
  std::optional<double> error;       // m; none: no (valid) report
  double simSeconds = 0;             // the task's time (the clock paused between tasks)
};

struct ChallengeResult {
  std::string terminated;            // "" or the reason
  CalibrationRunResult calibration;  // phase 1 (empty when skipped)
  bool calibrationSkipped = false;
  double calibrationSeconds = 0, calibrationWall = 0;
  double evaluationSeconds = 0, evaluationWall = 0;
  std::array<Eigen::Vector2d, 2> phaseOneBalls{}, phaseTwoBalls{};
  std::vector<ChallengeTaskResult> tasks;
  int falls = 0;
  std::vector<ChallengeEvent> events;  // t: simulated seconds since the first placement
  nlohmann::json robot;
  std::string headId;
  double pathLength = 0;
  std::vector<ChallengeSession::Track> track;
  std::vector<std::string> imagesWritten;
};

ChallengeResult runChallenge(const ChallengeOptions& options);

// What a seed decides when the options leave it open: the injected offsets (uniform in
// +-maxOffsetDeg per parameter) and the start side. calibration-challenge and eval challenge
// draw the same, so that a trial's seed replays it.
struct ChallengeDraw {
  CameraCalibration offsets;
  int side = -1;
};
ChallengeDraw challengeDraw(std::uint64_t seed, double maxOffsetDeg = 3);

// Phase 2's balls from the seed: one per half inside the field, at least clearance from every
// line, mark and the other ball, and 0.6 m from the start and the three spots.
std::array<Eigen::Vector2d, 2> phaseTwoBalls(const FieldDimensions& field, std::uint64_t seed, int side);
// Throws nao::Error(source, ...) naming the ball when one lies outside the field or on a line.
void checkBalls(const FieldDimensions& field, const std::array<Eigen::Vector2d, 2>& balls, const std::string& source);

// What the referee hears in "The ball is at: x y" (whole millimetres, as the rules' sentence);
// anything else (a missing number, a decimal point, trailing words) is no valid report.
std::optional<Eigen::Vector2d> parseBallSentence(const std::string& text);

// The referee's rounding: errors to 0.1 m, times to 5 s.
double roundTo(double value, double step);

nlohmann::json challengeJson(const ChallengeOptions& options, const ChallengeResult& result);

}  // namespace nao::sim
