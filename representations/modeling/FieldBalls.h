#pragma once
// Where the balls lie on the field, one per half (FieldBallLocator provides it): the
// calibration challenge's phase 2 asks for the ball in each half in field coordinates. Each
// half keeps its own estimate, so a second ball elsewhere never pulls it; the report's value
// is the median of the observations made from near (closeDistance), which carry the least of
// the camera's and the localization's errors.
#include <Eigen/Core>

namespace nao {

struct FieldBalls {
  struct Ball {
    bool seen = false;                                   // a cluster of observations supports it
    Eigen::Vector2d position = Eigen::Vector2d::Zero();  // field, m: median of the cluster
    int support = 0;                                     // observations in the cluster
    double lastSeen = -1;                                // s, exposure of the newest of them
    int close = 0;                                       // of them made from within closeDistance
    Eigen::Vector2d closePosition = Eigen::Vector2d::Zero();  // median of the newest close ones
    double closeSpread = 0;                              // m: their median distance from closePosition
  };
  Ball own;       // x < 0 (the robot's own half)
  Ball opponent;  // x > 0
  int resets = 0; // counts the resets (a challenge start clears both halves)

  const Ball& half(bool ownHalf) const { return ownHalf ? own : opponent; }
};

}  // namespace nao
