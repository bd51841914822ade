#pragma once
// A scripted situation (`match --situation FILE.json`, the file format in ../shared/design.md):
// the GameController's state and clock, robots placed and either running their robot program or
// driven by a script, balls placed or kicked at a given time by a given team. The referee judges
// it as a game, so each rule gets a situation that must produce exactly its call, and legal play
// one that must produce none. Scripted robots are the referee's props: their steps may use the
// truth (walk_to a field pose); a robot with "program": true is a real player and reads nothing
// but its own sensors.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "robot/nao/GameController.h"

namespace nao::sim {

struct SituationStep {
  double t = 0;            // s from the situation's start
  std::string action;      // walk_to, stand, sit, fall, lie, get_up, kick, none
  Eigen::Vector3d pose = Eigen::Vector3d::Zero();  // walk_to: x, y (m), theta (rad)
  double directionDeg = 0, speed = 0;              // kick: field frame direction, ball speed m/s
};

struct SituationRobot {
  bool present = false;    // absent: parked off the carpet, not judged
  Eigen::Vector3d pose = Eigen::Vector3d::Zero();  // x, y (m), theta (rad)
  bool program = false;    // runs its robot program (else the script drives it)
  std::vector<SituationStep> script;
};

struct SituationBall {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  std::optional<Eigen::Vector2d> velocity;  // given at `at`, as kicked by team `by`
  double at = 0;
  int by = -1;  // 0 home, 1 away
};

struct Situation {
  gc::State state = gc::State::Playing;
  double secsRemaining = 300;
  double seconds = 20;   // how long it runs
  bool firstHalf = true;
  std::string field;     // a field file ("" = the command's)
  std::array<SituationRobot, 2> robots;  // home, away
  std::vector<SituationBall> balls;      // up to 4
};

// Reads and checks a situation file; throws nao::Error(path, "key: problem") naming the first
// problem (unknown keys included). Poses must lie on the carpet, times ascend.
Situation loadSituation(const std::string& path, double halfSeconds = 300);

}  // namespace nao::sim
