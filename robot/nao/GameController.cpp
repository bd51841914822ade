#include "robot/nao/GameController.h"

#include <arpa/inet.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "robot/Error.h"

namespace nao::gc {
namespace {

const char* const kWhere = "GameController packet";
const char* const kReturnWhere = "GameController return packet";

std::string printableHeader(const std::uint8_t* p, std::size_t n) {
  std::string s;
  for (std::size_t i = 0; i < n; ++i) {
    if (p[i] >= 0x20 && p[i] < 0x7f) {
      s += static_cast<char>(p[i]);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", p[i]);
      s += hex;
    }
  }
  return s;
}

// Little-endian field access with a cursor that never leaves the checked length.
class Reader {
 public:
  explicit Reader(const std::uint8_t* p) : p_(p) {}
  std::uint8_t u8() { return p_[pos_++]; }
  std::uint16_t u16() {
    const std::uint16_t v = static_cast<std::uint16_t>(p_[pos_] | (p_[pos_ + 1] << 8));
    pos_ += 2;
    return v;
  }
  std::int16_t i16() { return static_cast<std::int16_t>(u16()); }
  float f32() {
    std::uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | p_[pos_ + static_cast<std::size_t>(i)];
    pos_ += 4;
    float f;
    std::memcpy(&f, &v, 4);
    return f;
  }
  std::size_t pos() const { return pos_; }
  void skip(std::size_t n) { pos_ += n; }

 private:
  const std::uint8_t* p_;
  std::size_t pos_ = 0;
};

template <std::size_t N>
class Writer {
 public:
  explicit Writer(std::array<std::uint8_t, N>& out) : out_(out) {}
  void u8(std::uint8_t v) { out_[pos_++] = v; }
  void u16(std::uint16_t v) {
    u8(static_cast<std::uint8_t>(v & 0xff));
    u8(static_cast<std::uint8_t>(v >> 8));
  }
  void i16(std::int16_t v) { u16(static_cast<std::uint16_t>(v)); }
  void f32(float f) {
    std::uint32_t v;
    std::memcpy(&v, &f, 4);
    for (int i = 0; i < 4; ++i) u8(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void bytes(const char* s, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) u8(static_cast<std::uint8_t>(s[i]));
  }
  std::size_t pos() const { return pos_; }

 private:
  std::array<std::uint8_t, N>& out_;
  std::size_t pos_ = 0;
};

std::uint8_t ranged(std::uint8_t v, std::uint8_t max, const char* field) {
  if (v > max)
    throw Error(kWhere, std::string(field) + ": " + std::to_string(v) + " is outside 0.." + std::to_string(max));
  return v;
}

}  // namespace

const char* stateName(State s) {
  switch (s) {
    case State::Initial: return "INITIAL";
    case State::Ready: return "READY";
    case State::Set: return "SET";
    case State::Playing: return "PLAYING";
    case State::Finished: return "FINISHED";
    case State::Standby: return "STANDBY";
  }
  return "?";
}

const char* penaltyName(Penalty p) {
  switch (p) {
    case Penalty::None: return "none";
    case Penalty::IllegalBallContact: return "illegal ball contact";
    case Penalty::PlayerPushing: return "pushing";
    case Penalty::IllegalMotionInSet: return "illegal motion in set";
    case Penalty::InactivePlayer: return "inactive player";
    case Penalty::IllegalPosition: return "illegal position";
    case Penalty::LeavingTheField: return "leaving the field";
    case Penalty::RequestForPickup: return "request for pick-up";
    case Penalty::LocalGameStuck: return "local game stuck";
    case Penalty::IllegalPositionInSet: return "illegal position in set";
    case Penalty::PlayerStance: return "player stance";
    case Penalty::IllegalMotionInStandby: return "illegal motion in standby";
    case Penalty::Substitute: return "substitute";
    case Penalty::Manual: return "manual";
  }
  return "?";
}

bool validPenalty(std::uint8_t c) { return c <= 11 || c == 14 || c == 15; }

GameControlData parseGameControlData(const std::uint8_t* data, std::size_t size) {
  if (size < 4 || std::memcmp(data, "RGme", 4) != 0)
    throw Error(kWhere, "header '" + printableHeader(data, std::min<std::size_t>(size, 4)) + "' is not 'RGme' (" +
                            std::to_string(size) + " bytes)");
  if (size < 5) throw Error(kWhere, "truncated after the header (" + std::to_string(size) + " bytes)");
  if (data[4] != kVersion)
    throw Error(kWhere, "version " + std::to_string(data[4]) + " arrived, this program speaks version " +
                            std::to_string(kVersion) + " (GameController3 since June 2024): update the GameController");
  if (size != kPacketSize)
    throw Error(kWhere, "length " + std::to_string(size) + " bytes, version 18 has " + std::to_string(kPacketSize));
  Reader r(data);
  r.skip(5);
  GameControlData d;
  d.packetNumber = r.u8();
  d.playersPerTeam = ranged(r.u8(), kMaxPlayers, "playersPerTeam");
  d.competitionPhase = ranged(r.u8(), 1, "competitionPhase");
  d.competitionType = ranged(r.u8(), 1, "competitionType");
  d.gamePhase = static_cast<GamePhase>(ranged(r.u8(), 3, "gamePhase"));
  d.state = static_cast<State>(ranged(r.u8(), 5, "state"));
  d.setPlay = static_cast<SetPlay>(ranged(r.u8(), 5, "setPlay"));
  d.firstHalf = ranged(r.u8(), 1, "firstHalf");
  d.kickingTeam = r.u8();
  d.secsRemaining = r.i16();
  d.secondaryTime = r.i16();
  for (int t = 0; t < 2; ++t) {
    TeamInfo& team = d.teams[static_cast<std::size_t>(t)];
    const std::string prefix = "teams[" + std::to_string(t) + "].";
    team.teamNumber = r.u8();
    team.fieldPlayerColour = ranged(r.u8(), 9, (prefix + "fieldPlayerColour").c_str());
    team.goalkeeperColour = ranged(r.u8(), 9, (prefix + "goalkeeperColour").c_str());
    team.goalkeeper = ranged(r.u8(), kMaxPlayers, (prefix + "goalkeeper").c_str());
    team.score = r.u8();
    team.penaltyShot = r.u8();
    team.singleShots = r.u16();
    team.messageBudget = r.u16();
    for (int p = 0; p < kMaxPlayers; ++p) {
      PlayerInfo& player = team.players[static_cast<std::size_t>(p)];
      player.penalty = r.u8();
      if (!validPenalty(player.penalty))
        throw Error(kWhere, prefix + "players[" + std::to_string(p) + "].penalty: " + std::to_string(player.penalty) +
                                " is not a penalty code");
      player.secsTillUnpenalised = r.u8();
    }
  }
  return d;
}

std::array<std::uint8_t, kPacketSize> serialize(const GameControlData& d) {
  std::array<std::uint8_t, kPacketSize> out{};
  Writer w(out);
  w.bytes("RGme", 4);
  w.u8(kVersion);
  w.u8(d.packetNumber);
  w.u8(d.playersPerTeam);
  w.u8(d.competitionPhase);
  w.u8(d.competitionType);
  w.u8(static_cast<std::uint8_t>(d.gamePhase));
  w.u8(static_cast<std::uint8_t>(d.state));
  w.u8(static_cast<std::uint8_t>(d.setPlay));
  w.u8(d.firstHalf);
  w.u8(d.kickingTeam);
  w.i16(d.secsRemaining);
  w.i16(d.secondaryTime);
  for (const TeamInfo& t : d.teams) {
    w.u8(t.teamNumber);
    w.u8(t.fieldPlayerColour);
    w.u8(t.goalkeeperColour);
    w.u8(t.goalkeeper);
    w.u8(t.score);
    w.u8(t.penaltyShot);
    w.u16(t.singleShots);
    w.u16(t.messageBudget);
    for (const PlayerInfo& p : t.players) {
      w.u8(p.penalty);
      w.u8(p.secsTillUnpenalised);
    }
  }
  return out;
}

ReturnData parseReturnData(const std::uint8_t* data, std::size_t size) {
  if (size < 4 || std::memcmp(data, "RGrt", 4) != 0)
    throw Error(kReturnWhere, "header '" + printableHeader(data, std::min<std::size_t>(size, 4)) + "' is not 'RGrt'");
  if (size < 5) throw Error(kReturnWhere, "truncated after the header");
  if (data[4] != kReturnVersion)
    throw Error(kReturnWhere, "version " + std::to_string(data[4]) + " arrived, expected " + std::to_string(kReturnVersion));
  if (size != kReturnSize)
    throw Error(kReturnWhere, "length " + std::to_string(size) + " bytes, expected " + std::to_string(kReturnSize));
  Reader r(data);
  r.skip(5);
  ReturnData d;
  d.playerNum = r.u8();
  d.teamNum = r.u8();
  d.fallen = r.u8();
  for (float& v : d.pose) v = r.f32();
  d.ballAge = r.f32();
  for (float& v : d.ball) v = r.f32();
  return d;
}

std::array<std::uint8_t, kReturnSize> serialize(const ReturnData& d) {
  std::array<std::uint8_t, kReturnSize> out{};
  Writer w(out);
  w.bytes("RGrt", 4);
  w.u8(kReturnVersion);
  w.u8(d.playerNum);
  w.u8(d.teamNum);
  w.u8(d.fallen);
  for (float v : d.pose) w.f32(v);
  w.f32(d.ballAge);
  for (float v : d.ball) w.f32(v);
  return out;
}

}  // namespace nao::gc

namespace nao {

const char* buttonEventName(ButtonEvent e) {
  switch (e) {
    case ButtonEvent::ChestPress: return "chest button";
    case ButtonEvent::StartCalibration: return "chest + head front (start calibration)";
    case ButtonEvent::StartCalibrationEvaluation: return "chest + head rear (start the calibration evaluation)";
    case ButtonEvent::Unstiffen: return "all head buttons (unstiffen)";
    case ButtonEvent::HeadTap: return "head tap";
  }
  return "?";
}

const ButtonState& ButtonInterface::update(const std::array<double, NumTouch>& touch, double time) {
  ButtonState& s = state_;
  s.events.clear();
  s.chest = touch[ChestButton] > 0.5;
  s.headFront = touch[HeadFront] > 0.5;
  s.headMiddle = touch[HeadMiddle] > 0.5;
  s.headRear = touch[HeadRear] > 0.5;

  int combo = 0;
  if (s.chest && s.headFront && !s.headRear) combo = 1;
  else if (s.chest && s.headRear && !s.headFront) combo = 2;
  else if (!s.chest && s.headFront && s.headMiddle && s.headRear) combo = 3;
  if (combo != combo_) {
    combo_ = combo;
    comboSince_ = time;
    comboFired_ = false;
  }
  if (combo_ != 0 && !comboFired_ && time - comboSince_ >= kHoldTime - 1e-9) {
    comboFired_ = true;
    s.events.push_back(combo_ == 1 ? ButtonEvent::StartCalibration
                                   : combo_ == 2 ? ButtonEvent::StartCalibrationEvaluation : ButtonEvent::Unstiffen);
  }

  // A tap: one head button at a time, no chest, released within kTapMin..kTapMax of the press.
  const int head = s.headFront + s.headMiddle + s.headRear;
  if (head > 0) {
    if (headSince_ < 0) {
      headSince_ = time;
      tapValid_ = true;
    }
    if (head > 1 || s.chest) tapValid_ = false;
  } else if (headSince_ >= 0) {
    const double held = time - headSince_;
    if (tapValid_ && held >= kTapMin - 1e-9 && held <= kTapMax + 1e-9) s.events.push_back(ButtonEvent::HeadTap);
    headSince_ = -1;
  }

  if (s.chest) {
    if (chestSince_ < 0) {
      chestSince_ = time;
      chestOnly_ = true;
    }
    if (s.headFront || s.headMiddle || s.headRear) chestOnly_ = false;
  } else if (chestSince_ >= 0) {
    if (chestOnly_) s.events.push_back(ButtonEvent::ChestPress);
    chestSince_ = -1;
  }
  return s;
}

int gc::bindUdp(const std::string& address, std::uint16_t port, std::uint16_t& bound) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) throw Error("--gc-port", std::string("socket: ") + std::strerror(errno));
  const int one = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(port);
  if (::inet_pton(AF_INET, address.c_str(), &addr.sin_addr) != 1) {
    ::close(fd);
    throw Error("--gc-address", "'" + address + "' is not an IPv4 address");
  }
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) < 0) {
    const std::string why = std::strerror(errno);
    ::close(fd);
    throw Error("--gc-port", "cannot bind UDP " + address + ":" + std::to_string(port) + ": " + why);
  }
  socklen_t len = sizeof addr;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  bound = ntohs(addr.sin_port);
  return fd;
}

GameController::GameController(Config config, Log log) : config_(std::move(config)), log_(std::move(log)) {
  if (!log_) log_ = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
  state_.teamNumber = config_.team;
  state_.playerNumber = config_.player;
  fd_ = gc::bindUdp(config_.bindAddress, config_.port, boundPort_);
}

GameController::~GameController() {
  if (fd_ >= 0) ::close(fd_);
}

void GameController::logRejected(const std::string& why, double now) {
  ++rejected_;
  // Once per distinct reason, then at most every 10 s: a wrong GameController sends 2 Hz.
  if (why != lastRejection_ || now - lastRejectionLog_ >= 10) {
    log_("gamecontroller: rejected " + why);
    lastRejection_ = why;
    lastRejectionLog_ = now;
  }
}

int GameController::receive(double now) {
  int accepted = 0;
  for (int i = 0; i < 64; ++i) {
    std::uint8_t buffer[1024];
    sockaddr_in from{};
    socklen_t len = sizeof from;
    const ssize_t n = ::recvfrom(fd_, buffer, sizeof buffer, MSG_DONTWAIT, reinterpret_cast<sockaddr*>(&from), &len);
    if (n < 0) break;
    if (handlePacket(buffer, static_cast<std::size_t>(n), now, &from)) ++accepted;
  }
  return accepted;
}

bool GameController::handlePacket(const std::uint8_t* data, std::size_t size, double now, const sockaddr_in* from) {
  gc::GameControlData d;
  try {
    d = gc::parseGameControlData(data, size);
  } catch (const Error& e) {
    logRejected(e.what(), now);
    return false;
  }
  if (config_.team <= 0) {
    if (!warnedTeam_) log_("gamecontroller: packets arrive, but no --team is set: ignoring them");
    warnedTeam_ = true;
    return false;
  }
  int own = -1;
  for (int t = 0; t < 2; ++t)
    if (d.teams[static_cast<std::size_t>(t)].teamNumber == config_.team) own = t;
  if (own < 0) {
    logRejected("GameController packet: for teams " + std::to_string(d.teams[0].teamNumber) + " and " +
                    std::to_string(d.teams[1].teamNumber) + ", we are team " + std::to_string(config_.team),
                now);
    return false;
  }
  const gc::TeamInfo& team = d.teams[static_cast<std::size_t>(own)];
  const gc::TeamInfo& other = d.teams[static_cast<std::size_t>(1 - own)];
  const GameState before = state_;
  GameState& s = state_;
  s.state = d.state;
  s.gamePhase = d.gamePhase;
  s.setPlay = d.setPlay;
  const gc::PlayerInfo& me = team.players[static_cast<std::size_t>(std::clamp(config_.player, 1, gc::kMaxPlayers) - 1)];
  s.penalty = static_cast<gc::Penalty>(me.penalty);
  s.secsTillUnpenalised = me.secsTillUnpenalised;
  s.firstHalf = d.firstHalf != 0;
  s.ownKickOff = d.kickingTeam == config_.team;
  s.secsRemaining = d.secsRemaining;
  s.secondaryTime = d.secondaryTime;
  s.ownScore = team.score;
  s.opponentScore = other.score;
  s.fieldPlayerColour = team.fieldPlayerColour;
  s.goalkeeper = team.goalkeeper == config_.player;
  s.fromGameController = true;
  s.lastPacketTime = now;
  s.packetNumber = d.packetNumber;
  if (from) gcAddress_ = *from;
  if (!before.fromGameController) log_("gamecontroller: following the GameController");
  if (s.state != before.state || !before.fromGameController)
    log_(std::string("game: ") + gc::stateName(s.state));
  if (s.penalty != before.penalty)
    log_(s.penalised() ? std::string("game: penalised (") + gc::penaltyName(s.penalty) + ")" : std::string("game: unpenalised"));
  return true;
}

bool GameController::gameControllerActive(double now) const {
  return state_.fromGameController && now - state_.lastPacketTime <= config_.timeout;
}

void GameController::chestButton(double now) {
  if (gameControllerActive(now)) {
    log_("game: chest button ignored, the GameController decides");
    return;
  }
  log_(pressChestButton(state_));
}

std::string pressChestButton(GameState& s) {
  s.fromGameController = false;
  if (s.state == gc::State::Initial) {
    s.state = gc::State::Playing;
    s.penalty = gc::Penalty::Manual;
    return "game: PLAYING, penalised (chest button)";
  }
  if (s.penalised()) {
    s.penalty = gc::Penalty::None;
    return "game: unpenalised (chest button)";
  }
  s.penalty = gc::Penalty::Manual;
  return "game: penalised (chest button)";
}

bool GameController::sendReturnIfDue(double now, const gc::ReturnData& data) {
  if (!gcAddress_ || !gameControllerActive(now) || now - lastReturn_ < config_.returnPeriod) return false;
  lastReturn_ = now;
  sockaddr_in to = *gcAddress_;
  to.sin_port = htons(config_.returnPort);
  const auto bytes = gc::serialize(data);
  return ::sendto(fd_, bytes.data(), bytes.size(), MSG_DONTWAIT, reinterpret_cast<const sockaddr*>(&to), sizeof to) ==
         static_cast<ssize_t>(bytes.size());
}

std::array<double, 3> chestColour(const GameState& s) {
  if (s.penalised()) return {1, 0, 0};
  switch (s.state) {
    case gc::State::Initial:
    case gc::State::Finished: return {0, 0, 0};
    case gc::State::Ready: return {0, 0, 1};
    case gc::State::Set: return {1, 1, 0};
    case gc::State::Playing: return {0, 1, 0};
    case gc::State::Standby: return {0, 1, 1};
  }
  return {0, 0, 0};
}

}  // namespace nao
