#pragma once
// The Autonomous Calibration Challenge's termination rules, judged from the simulator's truth
// once per robot cycle (../shared/reference/calibration-challenge.md, "Termination"): three
// falls; a fall without standing again within 60 s; leaving the field (every corner of both
// soles beyond the outer edge of the boundary lines: standing on a line, as the goal-centre
// tasks need, is in); touching a ball (the world latches every robot-ball touch in every
// physics step). The phase's 10 min are the phase loop's to judge.
#include <string>
#include <vector>

namespace nao::sim {

class World;

// A moment the referee noted: buttons, speech, arm, falls, contacts, the termination.
struct ChallengeEvent {
  double t = 0;  // s, simulated
  std::string kind, text;
};

class ChallengeReferee {
 public:
  struct Params {
    double fallTilt = 50;      // deg of torso tilt: fallen beyond this ...
    double fallHeight = 0.15;  // m: ... or with the torso below this
    double upTilt = 20;        // deg: standing again within this ...
    // m: ... and above this. The torso stands 0.227 m high, walks at 0.222 and sags a few mm
    // under a randomised robot's load; kneeling upright it is about 0.19.
    double upHeight = 0.20;
    double getUpLimit = 60;    // s from a fall to standing again
    int maxFalls = 3;
  };

  ChallengeReferee() = default;
  explicit ChallengeReferee(const Params& params) : params_(params) {}
  // Judges the world as it is now; calls go to `events`. Returns the termination reason, ""
  // while the run goes on (and after a termination, the same reason again).
  const std::string& check(World& world, int robot, std::vector<ChallengeEvent>& events);
  // The referee placed the robot (standing): no fall is pending.
  void placed() { fallenSince_ = -1; }
  const std::string& terminated() const { return terminated_; }
  int falls() const { return falls_; }
  // Whether every sole corner lies beyond the outer edge of the boundary lines.
  static bool leftField(const World& world, int robot);
  // Whether the robot shows a raised arm as the referee reads it: standing (torso within
  // upTilt of upright) with a hand above the head. A robot on the ground waving its arms while it
  // gets up raises none.
  bool armRaised(const World& world, int robot) const;

 private:
  Params params_;
  std::string terminated_;
  int falls_ = 0;
  double fallenSince_ = -1;
};

}  // namespace nao::sim
