#pragma once
// The SPL GameController protocol (struct version 18, ../shared/reference/protocols.md) and
// the robot's game state: packet parsing and building (the robot and the simulator's
// in-process GameController share this code), a UDP receiver that answers with return
// packets, and the button interface used when no GameController runs.
#include <netinet/in.h>

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "representations/infrastructure/ButtonState.h"
#include "representations/infrastructure/GameState.h"
#include "robot/JointIds.h"

namespace nao::gc {

inline constexpr std::uint8_t kVersion = 18;
inline constexpr std::size_t kPacketSize = 118;
inline constexpr std::uint8_t kReturnVersion = 4;
inline constexpr std::size_t kReturnSize = 32;
inline constexpr int kMaxPlayers = 20;
inline constexpr std::uint16_t kPort = 3838;
inline constexpr std::uint16_t kReturnPort = 3939;

const char* stateName(State s);
const char* penaltyName(Penalty p);
bool validPenalty(std::uint8_t code);
inline constexpr std::uint8_t kNoTeam = 255;  // kickingTeam when nobody kicks

struct PlayerInfo {
  std::uint8_t penalty = 0;
  std::uint8_t secsTillUnpenalised = 0;
};

struct TeamInfo {
  std::uint8_t teamNumber = 0;
  std::uint8_t fieldPlayerColour = 0, goalkeeperColour = 0;
  std::uint8_t goalkeeper = 1;  // player number 1..20
  std::uint8_t score = 0;
  std::uint8_t penaltyShot = 0;
  std::uint16_t singleShots = 0;
  std::uint16_t messageBudget = 0;
  std::array<PlayerInfo, kMaxPlayers> players{};
};

// RoboCupGameControlData v18, field by field.
struct GameControlData {
  std::uint8_t packetNumber = 0;
  std::uint8_t playersPerTeam = 7;
  std::uint8_t competitionPhase = 0;  // 0 round robin, 1 play-off
  std::uint8_t competitionType = 0;   // 0 normal, 1 most passes
  GamePhase gamePhase = GamePhase::Normal;
  State state = State::Initial;
  SetPlay setPlay = SetPlay::None;
  std::uint8_t firstHalf = 1;
  std::uint8_t kickingTeam = kNoTeam;
  std::int16_t secsRemaining = 600;
  std::int16_t secondaryTime = 0;
  std::array<TeamInfo, 2> teams{};
};

// RoboCupGameControlReturnData v4.
struct ReturnData {
  std::uint8_t playerNum = 1;
  std::uint8_t teamNum = 0;
  std::uint8_t fallen = 0;
  std::array<float, 3> pose{};  // x mm, y mm, theta rad (field, own team attacks +x)
  float ballAge = -1;           // s since the ball was seen, -1 never
  std::array<float, 2> ball{};  // mm, robot-relative
};

// Throw nao::Error("GameController packet", why): wrong header, wrong version (naming the
// version that arrived), wrong length, or a field outside its documented range.
GameControlData parseGameControlData(const std::uint8_t* data, std::size_t size);
std::array<std::uint8_t, kPacketSize> serialize(const GameControlData& data);
ReturnData parseReturnData(const std::uint8_t* data, std::size_t size);
// A non-blocking UDP socket bound to address:port (port 0: any free one), SO_REUSEADDR;
// `bound` gets the port. Throws nao::Error("--gc-address" or "--gc-port", why).
int bindUdp(const std::string& address, std::uint16_t port, std::uint16_t& bound);
std::array<std::uint8_t, kReturnSize> serialize(const ReturnData& data);

}  // namespace nao::gc

namespace nao {

class ButtonInterface {
 public:
  static constexpr double kHoldTime = 1.0;                    // s
  static constexpr double kTapMin = 0.05, kTapMax = kHoldTime;  // s a head tap lasts
  // touch: the Touch array (LoLA order); time: backend seconds. Returns this cycle's state.
  const ButtonState& update(const std::array<double, NumTouch>& touch, double time);
  const ButtonState& state() const { return state_; }

 private:
  ButtonState state_;
  double chestSince_ = -1;
  bool chestOnly_ = true;          // nothing else touched during this chest press
  double comboSince_ = -1;         // when the current combination started
  int combo_ = 0;                  // which combination is held (bit mask)
  bool comboFired_ = false;
  double headSince_ = -1;  // when a head button was first pressed, none before
  bool tapValid_ = false;  // one head button alone so far, no chest
};

// Receives GameController packets on UDP (non-blocking, polled once a cycle), keeps the game
// state and sends return packets to the GameController that sent them.
class GameController {
 public:
  struct Config {
    int team = 0;    // 0: no team; every packet is ignored (with one log line)
    int player = 1;  // 1..20
    std::uint16_t port = gc::kPort;                // 0: any free port (tests)
    std::uint16_t returnPort = gc::kReturnPort;
    std::string bindAddress = "0.0.0.0";
    double returnPeriod = 1.0;  // s between return packets
    double timeout = 5.0;       // s without packets: the GameController is gone
  };
  using Log = std::function<void(const std::string&)>;

  explicit GameController(Config config, Log log = {});  // throws nao::Error when the port is taken
  ~GameController();
  GameController(const GameController&) = delete;
  GameController& operator=(const GameController&) = delete;

  // Reads every pending datagram and applies the valid ones; returns how many were accepted.
  int receive(double now);
  // One datagram from `from` (network byte order address): validates and applies it.
  bool handlePacket(const std::uint8_t* data, std::size_t size, double now, const sockaddr_in* from = nullptr);
  // The chest button without a GameController: penalise / unpenalise; from INITIAL, play
  // (penalised first, as the rules have it).
  void chestButton(double now);
  // Sends a return packet when one is due and a GameController was heard recently.
  bool sendReturnIfDue(double now, const gc::ReturnData& data);
  bool gameControllerActive(double now) const;

  const GameState& state() const { return state_; }
  std::uint16_t port() const { return boundPort_; }
  int rejected() const { return rejected_; }

 private:
  void logRejected(const std::string& why, double now);

  Config config_;
  Log log_;
  int fd_ = -1;
  std::uint16_t boundPort_ = 0;
  GameState state_;
  std::optional<sockaddr_in> gcAddress_;
  double lastReturn_ = -1e9;
  std::string lastRejection_;
  double lastRejectionLog_ = -1e9;
  int rejected_ = 0;
  bool warnedTeam_ = false;
};

// The chest button without a GameController (the rules' manual part): from INITIAL to
// PLAYING, penalised; after that each press unpenalises or penalises. Returns what it did
// (a log line).
std::string pressChestButton(GameState& state);

// The chest LED colour the rules ask for (RGB 0..1): off in INITIAL and FINISHED, blue READY,
// yellow SET, green PLAYING, red when penalised, cyan STANDBY.
std::array<double, 3> chestColour(const GameState& state);

}  // namespace nao
