#pragma once
// Kicking in the simulator: a ball in front of the robot, a kick direction; the robot (fed the
// ball's true position as its ball percept) walks to the kick pose and kicks. Measured by ground
// truth: how far the ball rolls, in which direction, whether the robot falls.
#include <cstdint>
#include <functional>
#include <vector>

#include "scenarios/WalkEval.h"

namespace nao::sim {

struct KickTrialOptions {
  double ballDistance = 0.5;    // m from the robot
  double ballBearing = 0;       // rad, robot frame
  double direction = 0;         // rad, robot frame at the start: where the ball should go
  double timeLimit = 30;        // s for approach and kick
  std::uint64_t seed = 1;
  bool randomize = false;
  RobotVariation variation;
  MotionEngine::Params params;
};

struct KickTrialResult {
  bool kicked = false;        // the engine reported the kick done
  double travel = 0;          // m, ball start to rest
  double directionError = 0;  // rad, |ball's direction - requested|
  double directionErrorSigned = 0;  // rad, ball's direction - requested (counter-clockwise positive)
  bool leftFoot = false;      // the ball lay left of the robot's heading when the kick was asked for
  double ballSpeed = 0;       // m/s, the fastest the ball went
  double time = 0;            // s until the kick was done
  int falls = 0;
  AppliedVariation variation;
};

KickTrialResult runKick(const KickTrialOptions& options);

struct KickEvalOptions {
  int trials = 20;
  std::uint64_t seed = 1;
  bool randomize = false;
  RobotVariation variation;
  MotionEngine::Params params;
  std::function<void(int done, int total)> progress;
};

struct KickEvalResult {
  std::vector<KickTrialResult> trials;
  int falls = 0, kicked = 0;
  double travelMedian = 0, directionErrorMedian = 0;
};

// Ball 0.3-0.8 m away within +-45 deg of the heading, direction within +-45 deg.
KickEvalResult evalKick(const KickEvalOptions& options);

}  // namespace nao::sim
