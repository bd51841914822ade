#pragma once
// The GameController of a simulated 1vs1 game: the official GameController's state logic for
// the 2021 1vs1 challenge (../shared/reference/referee-and-match.md), without its socket and
// paced by simulated time. INITIAL -> READY (at most 45 s) -> SET -> PLAYING (after the
// whistle) -> FINISHED at the end of a half; a global game stuck goes back to READY with the
// clock stopped; penalties with the rules' durations (standard 45 s + 10 s per earlier
// standard one of the team; fallen and inactive 45 s; illegal position in SET 15 s; motion in
// SET until PLAYING), not running in SET and ending with the half; at most 3 hardware-related
// penalties per robot, the 4th excludes it. Its packets are the v18 packets a NAO decodes
// (gc::serialize): the robots receive what a real GameController would send.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "robot/nao/GameController.h"

namespace nao::sim {

// The rule behind a penalty (a referee call's rule name, docs: design.md "Situations").
enum class PenaltyRule {
  LeavingTheField, HalfwayLine, GoalArea, FallenRobot, InactiveRobot, PlayerStance, PlayingWithArms,
  IllegalPositionInSet, MotionInSet, RequestForPickup
};
const char* ruleName(PenaltyRule rule);
// Throws nao::Error("rule", ...) naming the unknown name.
PenaltyRule ruleNamed(const std::string& name);
gc::Penalty penaltyCode(PenaltyRule rule);

class GameControllerSim {
 public:
  struct Config {
    std::array<int, 2> teams{5, 6};    // team numbers: home, away
    std::array<int, 2> colours{0, 1};  // field player colours (protocol codes)
    int players = 1;                   // per team
    double halfSeconds = 300;
    double readyLimit = 45;     // s: READY ends at the latest then
    double whistleDelay = 5;    // s from SET to PLAYING
    double packetPeriod = 0.5;  // s: the GameController sends at about 2 Hz
    double standardPenalty = 45, penaltyIncrement = 10;
    double hardwarePenalty = 45;  // fallen, inactive, pick-up
    double illegalPositionInSetPenalty = 15;
    int hardwarePenaltyLimit = 3;
    int maxExtensions = 5;
    double extensionSeconds = 60;
  };
  struct Event {
    double t = 0;
    std::string kind;  // "state", "penalty", "unpenalise", "excluded", "score", "half", "extension", "coin_toss"
    std::string text;
    int team = -1;  // 0 home, 1 away
  };

  GameControllerSim();
  explicit GameControllerSim(const Config& config);

  // Advances the clocks to `t` (simulated s, never backwards): READY's limit, the whistle,
  // the half's clock in PLAYING, penalty times; the end of a half.
  void update(double t);
  // The operator's buttons.
  void ready(double t);        // INITIAL -> READY (the kick-off)
  void set(double t);          // READY -> SET (every robot in position before the limit)
  void globalGameStuck(double t);  // PLAYING -> READY, the clock stopped
  void startSecondHalf(double t);  // after the first half's FINISHED: INITIAL, second half
  // A scripted situation's start (match --situation): this state, this much of the half left.
  void startAt(gc::State state, double secsRemaining, bool firstHalf, double t);
  // An external GameController's packet as the authority (match --gc udp): its state, half,
  // clock, scores and penalties replace this one's, each change logged as the own would be;
  // update() then only keeps the time. Returns false (nothing taken) for a packet without
  // this game's teams.
  bool follow(const gc::GameControlData& packet, double t);
  bool external() const { return external_; }
  // A point for `team` (0 home, 1 away): the score, the state stays PLAYING.
  void point(int team, double t);
  // Penalises a robot (player 1..players) by the rule; returns the removal time in s (0 when
  // the robot was excluded, -1 for motion in SET: until PLAYING). Ignored (returns 0) for a
  // robot already penalised or excluded.
  double penalise(int team, int player, PenaltyRule rule, double t);
  // The coin toss after the last extension: decides the winner, from `coin` (0 or 1).
  void coinToss(int coin, double t);

  gc::State state() const { return data_.state; }
  bool firstHalf() const { return data_.firstHalf != 0; }
  bool finished() const;  // the game is over (second half or last extension ended, or a toss)
  double secsRemaining() const { return remaining_; }
  int score(int team) const { return data_.teams.at(static_cast<std::size_t>(team)).score; }
  int extensions() const { return extensions_; }
  int winner() const;  // 0, 1, or -1 (a draw so far)
  bool penalised(int team, int player) const;
  bool excluded(int team, int player) const;
  double penaltyLeft(int team, int player) const;
  int hardwarePenalties(int team, int player) const;
  const std::vector<Event>& events() const { return events_; }

  // The packet as the GameController would broadcast it now (the packet number counts up).
  std::array<std::uint8_t, gc::kPacketSize> packet();
  // Whether a packet is due at `t` (about 2 Hz); marks it sent.
  bool packetDue(double t);
  // The state as a packet holds it (without counting a packet).
  const gc::GameControlData& data() const { return data_; }

 private:
  struct Robot {
    gc::Penalty penalty = gc::Penalty::None;
    double left = 0;         // s of removal left; < 0: until PLAYING (motion in SET)
    int hardware = 0;        // hardware-related penalties so far
    bool excluded = false;
  };
  Robot& robot(int team, int player);
  const Robot& robot(int team, int player) const;
  void go(gc::State s, double t);
  void endOfHalf(double t);
  void clearPenalties(double t);
  void sync();
  void log(double t, const std::string& kind, const std::string& text, int team = -1);

  Config config_;
  gc::GameControlData data_;
  std::array<std::vector<Robot>, 2> robots_;
  std::array<int, 2> standardPenalties_{};  // per team, for the increment
  double now_ = 0;
  double since_ = 0;  // when the current state began
  double remaining_ = 0;
  int extensions_ = 0;
  int tossWinner_ = -1;
  bool over_ = false;
  bool external_ = false;
  double lastPacket_ = -1e9;
  std::vector<Event> events_;
};

}  // namespace nao::sim
