#pragma once
// A simulated 1vs1 game (../shared/reference/one-vs-one.md): two robot programs, each on its
// own simulated NAO with its own two cameras, a GameController (GameControllerSim) whose v18
// packets each robot's own receiver (robot/nao/GameController.h) decodes, and the referee's
// rules (BallRules, RobotRules) judged from the simulator's truth. The referee places robots
// and balls (the start, SET, penalties and their returns, balls out, the ball back to a
// scorer); nothing moves a robot while it plays, and no robot program reads the truth.
// Frames: the field frame; in the first half the home team defends the goal at negative x.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "perception/FieldDimensions.h"
#include "robot/Debug.h"
#include "scenarios/Situation.h"
#include "sim/Lighting.h"
#include "sim/VenueLook.h"

namespace nao::sim {

struct MatchOptions {
  FieldDimensions field;
  std::string robotModel;  // empty: models/nao_v6.xml
  VenueLook venue;         // how the venue looks (sim/VenueLook.h)
  Lighting lighting;
  std::uint64_t seed = 1;
  bool randomize = false;     // both robots foreign (masses, joint offsets, floor friction)
  double halfSeconds = 300;   // the rules' 5 min
  double seconds = 0;         // > 0: stop after this much simulated time (a short game)
  std::array<int, 2> teams{5, 6};  // home (our robot program), away
  // The away robot's program: "self" (ours, as home), "baseline" (ours playing the scripted
  // baseline: to the ball, kick at the goal) or a configuration folder (modules.json, parameters/).
  std::string opponent = "self";
  bool replay = false;        // record MatchResult::replay (scenarios/MatchReplay.h)
  // Non-empty: pictures into this folder (made if missing): the field from above (true robots
  // and balls, each robot's believed pose and ball) every 10 simulated s, at each point and
  // referee call and at the end; with the vision, each robot's two camera images at those moments.
  std::string imagesDir;
  // "vision": both cameras rendered and seen by the vision; "oracle": the fast percept mode
  // (no rendering; OracleVision makes the percepts from the simulator's view, sim/OracleCamera.h).
  std::string percepts = "vision";
  // A scripted situation instead of a game (scenarios/Situation.h): its state, clock, robots,
  // scripts and balls; no operator (no kick-off, no SET, no balls at SET); it runs its seconds.
  std::optional<Situation> situation;
  std::function<void(double simTime, const std::string& status)> progress;  // about every 10 simulated s
  DebugChannels* debug = nullptr;  // the home robot program's debug channels (`match --debug`)
  // "inprocess": the simulated GameController runs the game; "udp": an external GameController
  // does, over UDP (scenarios/GameControllerLink.h): the match takes its packets on gcPort,
  // hands them to both robots, whose return packets go to its gcReturnPort; the simulation
  // runs at real time, the referee's calls and points go to the event log only (the operator
  // penalises and scores), and no packet within gcWait wall seconds fails the match.
  std::string gc = "inprocess";
  std::uint16_t gcPort = 3838, gcReturnPort = 3939;
  double gcWait = 30;
};

// Where a match's wall time went, in seconds. The game's loop: physics, images, cognition,
// motion and the rest (the referee, the GameController).
struct MatchWallTime {
  double setup = 0;      // building the world and both robot programs, before the first step
  double physics = 0;    // World::stepCycle
  double images = 0;     // rendering the cameras, or the oracle's views
  double cognition = 0;  // both robot programs' cognition runs
  double motion = 0;     // both robot programs' motion cycles
};

struct MatchResult {
  nlohmann::json json;  // the `match` contract (docs: design.md): score, points_by_kind, events, robots, ...
  int homeScore = 0, awayScore = 0;
  std::string state;    // the GameController's last state
  double simSeconds = 0, wallSeconds = 0;
  MatchWallTime wall;
  std::string glVendor, glRenderer, glPlatform;  // the renderer's OpenGL; empty in the fast percept mode
  nlohmann::json replay;  // replayData's JSON when MatchOptions::replay
};

MatchResult runMatch(const MatchOptions& options);

}  // namespace nao::sim
