#pragma once
// Getting up in the simulator: the standing robot is pushed over (onto its front or back), lies
// still, is asked to stand, and has a time limit to be on its feet again (ground truth).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "controllers/FallDetector.h"
#include "scenarios/WalkEval.h"

namespace nao::sim {

struct GetUpTrialOptions {
  FallDirection side = FallDirection::Front;
  double timeLimit = 15;  // s from the moment the robot lies still
  std::uint64_t seed = 1;
  bool randomize = false;
  RobotVariation variation;
  MotionEngine::Params params;
};

struct GetUpTrialResult {
  bool fell = false;                 // lying when asked to stand (else the trial failed)
  bool fellOnRequestedSide = false;
  bool success = false;   // upright (tilt < 20 deg, torso above 0.2 m) and standing 1 s, within the limit
  double time = -1;       // s from lying still to upright (when success)
  int attempts = 0;
  double maxTiltAfter = 0;  // rad, the second after getting up
  AppliedVariation variation;
};

GetUpTrialResult runGetUp(const GetUpTrialOptions& options);

struct GetUpEvalOptions {
  int trials = 20;  // per side
  std::uint64_t seed = 1;
  bool randomize = false;
  RobotVariation variation;
  double timeLimit = 15;
  MotionEngine::Params params;
  std::function<void(int done, int total)> progress;
};

struct GetUpSideResult {
  std::string name;  // "front", "back"
  int successes = 0;
  double successRate = 0;
  double medianTime = 0;      // of the successes
  std::vector<double> times;  // per trial, -1 = failed
};

struct GetUpEvalResult {
  std::vector<GetUpSideResult> sides;
};

GetUpEvalResult evalGetUp(const GetUpEvalOptions& options);

}  // namespace nao::sim
