#include "scenarios/GameControllerSim.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "robot/Error.h"

namespace nao::sim {

namespace {

struct RuleInfo {
  PenaltyRule rule;
  const char* name;
  gc::Penalty code;
};

constexpr RuleInfo kRules[] = {
    {PenaltyRule::LeavingTheField, "leaving_the_field", gc::Penalty::LeavingTheField},
    {PenaltyRule::HalfwayLine, "halfway_line", gc::Penalty::LeavingTheField},
    {PenaltyRule::GoalArea, "goal_area", gc::Penalty::LeavingTheField},
    {PenaltyRule::FallenRobot, "fallen_robot", gc::Penalty::InactivePlayer},
    {PenaltyRule::InactiveRobot, "inactive_robot", gc::Penalty::InactivePlayer},
    {PenaltyRule::PlayerStance, "player_stance", gc::Penalty::PlayerStance},
    {PenaltyRule::PlayingWithArms, "playing_with_arms", gc::Penalty::IllegalBallContact},
    {PenaltyRule::IllegalPositionInSet, "illegal_position_in_set", gc::Penalty::IllegalPositionInSet},
    {PenaltyRule::MotionInSet, "motion_in_set", gc::Penalty::IllegalMotionInSet},
    {PenaltyRule::RequestForPickup, "request_for_pickup", gc::Penalty::RequestForPickup},
};

const RuleInfo& info(PenaltyRule rule) {
  for (const auto& r : kRules)
    if (r.rule == rule) return r;
  return kRules[0];
}

bool hardwareRelated(PenaltyRule rule) {
  return rule == PenaltyRule::FallenRobot || rule == PenaltyRule::InactiveRobot || rule == PenaltyRule::RequestForPickup;
}

// Whole seconds as the GameController shows them (rounded up, clamped to the field's range).
template <typename T>
T shown(double seconds) {
  const double s = std::ceil(std::max(0.0, seconds) - 1e-9);
  return static_cast<T>(std::min<double>(s, std::numeric_limits<T>::max()));
}

}  // namespace

const char* ruleName(PenaltyRule rule) { return info(rule).name; }

PenaltyRule ruleNamed(const std::string& name) {
  std::string known;
  for (const auto& r : kRules) {
    if (name == r.name) return r.rule;
    known += known.empty() ? r.name : std::string(", ") + r.name;
  }
  throw Error("rule", "unknown rule '" + name + "' (known: " + known + ")");
}

gc::Penalty penaltyCode(PenaltyRule rule) { return info(rule).code; }

GameControllerSim::GameControllerSim() : GameControllerSim(Config{}) {}

GameControllerSim::GameControllerSim(const Config& config) : config_(config) {
  if (config_.players < 1 || config_.players > gc::kMaxPlayers)
    throw Error("GameController", "players per team must be 1.." + std::to_string(gc::kMaxPlayers));
  if (!(config_.halfSeconds > 0) || config_.halfSeconds > 32767)
    throw Error("GameController", "half length must be in (0, 32767] s");
  data_.playersPerTeam = static_cast<std::uint8_t>(config_.players);
  for (std::size_t i = 0; i < 2; ++i) {
    data_.teams[i].teamNumber = static_cast<std::uint8_t>(config_.teams[i]);
    data_.teams[i].fieldPlayerColour = static_cast<std::uint8_t>(config_.colours[i]);
    data_.teams[i].goalkeeperColour = static_cast<std::uint8_t>(config_.colours[i]);
    robots_[i].assign(static_cast<std::size_t>(config_.players), Robot{});
  }
  data_.kickingTeam = gc::kNoTeam;  // 1vs1: both robots may play the ball from the start
  remaining_ = config_.halfSeconds;
  sync();
}

GameControllerSim::Robot& GameControllerSim::robot(int team, int player) {
  if (team < 0 || team > 1 || player < 1 || player > config_.players)
    throw Error("GameController", "no robot " + std::to_string(player) + " in team " + std::to_string(team));
  return robots_[static_cast<std::size_t>(team)][static_cast<std::size_t>(player - 1)];
}

const GameControllerSim::Robot& GameControllerSim::robot(int team, int player) const {
  return const_cast<GameControllerSim*>(this)->robot(team, player);
}

void GameControllerSim::log(double t, const std::string& kind, const std::string& text, int team) {
  events_.push_back({t, kind, text, team});
}

void GameControllerSim::go(gc::State s, double t) {
  data_.state = s;
  since_ = t;
  log(t, "state", gc::stateName(s));
  sync();
}

void GameControllerSim::update(double t) {
  const double dt = std::max(0.0, t - now_);
  now_ = std::max(now_, t);
  if (external_) return;  // the external GameController runs the clocks
  // Penalty time runs in READY and PLAYING, not in SET (the rules) nor outside play.
  if (data_.state == gc::State::Ready || data_.state == gc::State::Playing) {
    for (int team = 0; team < 2; ++team)
      for (int p = 1; p <= config_.players; ++p) {
        Robot& r = robot(team, p);
        if (r.penalty == gc::Penalty::None || r.excluded || r.left < 0) continue;
        r.left -= dt;
        if (r.left <= 1e-9) {
          r.penalty = gc::Penalty::None;
          r.left = 0;
          log(t, "unpenalise", "player " + std::to_string(p), team);
        }
      }
  }
  switch (data_.state) {
    case gc::State::Ready:
      if (t - since_ >= config_.readyLimit - 1e-9) set(t);
      break;
    case gc::State::Set:
      if (t - since_ >= config_.whistleDelay - 1e-9) {
        for (int team = 0; team < 2; ++team)
          for (int p = 1; p <= config_.players; ++p) {
            Robot& r = robot(team, p);
            if (r.penalty == gc::Penalty::IllegalMotionInSet) {
              r.penalty = gc::Penalty::None;
              r.left = 0;
              log(t, "unpenalise", "player " + std::to_string(p), team);
            }
          }
        go(gc::State::Playing, t);
      }
      break;
    case gc::State::Playing:
      remaining_ -= dt;
      if (remaining_ <= 1e-9) endOfHalf(t);
      break;
    default:
      break;
  }
  sync();
}

void GameControllerSim::ready(double t) {
  if (data_.state != gc::State::Initial || over_) throw Error("GameController", "READY needs INITIAL");
  now_ = std::max(now_, t);
  go(gc::State::Ready, t);
}

void GameControllerSim::set(double t) {
  if (data_.state != gc::State::Ready) throw Error("GameController", "SET needs READY");
  now_ = std::max(now_, t);
  go(gc::State::Set, t);
}

void GameControllerSim::globalGameStuck(double t) {
  if (data_.state != gc::State::Playing) throw Error("GameController", "a global game stuck needs PLAYING");
  now_ = std::max(now_, t);
  log(t, "global_game_stuck", "");
  go(gc::State::Ready, t);
}

void GameControllerSim::startSecondHalf(double t) {
  if (data_.state != gc::State::Finished || !firstHalf() || over_)
    throw Error("GameController", "the second half needs the first half finished");
  now_ = std::max(now_, t);
  data_.firstHalf = 0;
  remaining_ = config_.halfSeconds;
  log(t, "half", "second half");
  go(gc::State::Initial, t);
}

void GameControllerSim::startAt(gc::State state, double secsRemaining, bool firstHalf, double t) {
  if (over_) throw Error("GameController", "the game is over");
  if (!(secsRemaining > 0) || secsRemaining > config_.halfSeconds)
    throw Error("GameController", "the time left must be in (0, half length]");
  now_ = std::max(now_, t);
  data_.firstHalf = firstHalf ? 1 : 0;
  remaining_ = secsRemaining;
  log(t, "situation", std::string(gc::stateName(state)) + (firstHalf ? ", first half" : ", second half"));
  go(state, t);
}

bool GameControllerSim::follow(const gc::GameControlData& in, double t) {
  std::array<const gc::TeamInfo*, 2> teams{};
  for (int team = 0; team < 2; ++team)
    for (const gc::TeamInfo& info : in.teams)
      if (info.teamNumber == config_.teams[static_cast<std::size_t>(team)]) teams[static_cast<std::size_t>(team)] = &info;
  if (!teams[0] || !teams[1]) return false;
  external_ = true;
  now_ = std::max(now_, t);
  if (in.firstHalf != data_.firstHalf) log(t, "half", in.firstHalf ? "first half" : "second half");
  if (in.state != data_.state) {
    data_.state = in.state;
    since_ = t;
    log(t, "state", gc::stateName(in.state));
  }
  data_.firstHalf = in.firstHalf;
  data_.setPlay = in.setPlay;
  data_.kickingTeam = in.kickingTeam;
  data_.secsRemaining = in.secsRemaining;
  data_.secondaryTime = in.secondaryTime;
  remaining_ = in.secsRemaining;
  for (int team = 0; team < 2; ++team) {
    const gc::TeamInfo& info = *teams[static_cast<std::size_t>(team)];
    gc::TeamInfo& own = data_.teams[static_cast<std::size_t>(team)];
    if (info.score != own.score) {
      own.score = info.score;
      log(t, "score", std::to_string(data_.teams[0].score) + ":" + std::to_string(data_.teams[1].score), team);
    }
    for (int p = 1; p <= config_.players; ++p) {
      Robot& r = robot(team, p);
      const gc::PlayerInfo& player = info.players[static_cast<std::size_t>(p - 1)];
      const auto penalty = static_cast<gc::Penalty>(player.penalty);
      if (penalty != r.penalty)
        log(t, penalty == gc::Penalty::None ? "unpenalise" : "penalty",
            "player " + std::to_string(p) + (penalty == gc::Penalty::None ? "" : std::string(": ") + gc::penaltyName(penalty)),
            team);
      r.penalty = penalty;
      r.left = player.secsTillUnpenalised;
      own.players[static_cast<std::size_t>(p - 1)] = player;
    }
  }
  over_ = in.state == gc::State::Finished && in.firstHalf == 0;
  return true;
}

void GameControllerSim::point(int team, double t) {
  if (data_.state != gc::State::Playing) throw Error("GameController", "a point needs PLAYING");
  auto& score = data_.teams.at(static_cast<std::size_t>(team)).score;
  score = static_cast<std::uint8_t>(std::min(255, score + 1));
  log(t, "score", std::to_string(data_.teams[0].score) + ":" + std::to_string(data_.teams[1].score), team);
  sync();
}

double GameControllerSim::penalise(int team, int player, PenaltyRule rule, double t) {
  Robot& r = robot(team, player);
  if (r.excluded || r.penalty != gc::Penalty::None) return 0;
  const std::string who = "player " + std::to_string(player) + ": " + ruleName(rule);
  if (hardwareRelated(rule) && ++r.hardware > config_.hardwarePenaltyLimit) {
    r.excluded = true;
    r.penalty = gc::Penalty::RequestForPickup;
    r.left = 0;
    log(t, "excluded", who, team);
    sync();
    return 0;
  }
  r.penalty = penaltyCode(rule);
  switch (rule) {
    case PenaltyRule::MotionInSet: r.left = -1; break;
    case PenaltyRule::IllegalPositionInSet: r.left = config_.illegalPositionInSetPenalty; break;
    case PenaltyRule::FallenRobot:
    case PenaltyRule::InactiveRobot:
    case PenaltyRule::RequestForPickup: r.left = config_.hardwarePenalty; break;
    default:
      r.left = config_.standardPenalty + config_.penaltyIncrement * standardPenalties_[static_cast<std::size_t>(team)]++;
      break;
  }
  log(t, "penalty", who, team);
  sync();
  return r.left;
}

void GameControllerSim::clearPenalties(double t) {
  for (int team = 0; team < 2; ++team)
    for (int p = 1; p <= config_.players; ++p) {
      Robot& r = robot(team, p);
      if (r.excluded || r.penalty == gc::Penalty::None) continue;
      r.penalty = gc::Penalty::None;
      r.left = 0;
      log(t, "unpenalise", "player " + std::to_string(p) + " (end of the half)", team);
    }
}

void GameControllerSim::endOfHalf(double t) {
  remaining_ = 0;
  clearPenalties(t);
  if (firstHalf()) {
    log(t, "half", "end of the first half");
    go(gc::State::Finished, t);
    return;
  }
  if (data_.teams[0].score == data_.teams[1].score && extensions_ < config_.maxExtensions) {
    // A draw: the game goes on for another minute, then the score is compared again.
    ++extensions_;
    data_.gamePhase = gc::GamePhase::Overtime;
    remaining_ = config_.extensionSeconds;
    log(t, "extension", std::to_string(extensions_));
    sync();
    return;
  }
  over_ = true;
  log(t, "half", extensions_ ? "end of the last extension" : "end of the second half");
  go(gc::State::Finished, t);
}

void GameControllerSim::coinToss(int coin, double t) {
  if (!over_ || winner() >= 0 || tossWinner_ >= 0) throw Error("GameController", "a coin toss needs a drawn, finished game");
  tossWinner_ = coin ? 1 : 0;
  log(t, "coin_toss", tossWinner_ ? "away" : "home", tossWinner_);
}

bool GameControllerSim::finished() const { return over_; }

int GameControllerSim::winner() const {
  if (tossWinner_ >= 0) return tossWinner_;
  if (data_.teams[0].score == data_.teams[1].score) return -1;
  return data_.teams[0].score > data_.teams[1].score ? 0 : 1;
}

bool GameControllerSim::penalised(int team, int player) const { return robot(team, player).penalty != gc::Penalty::None; }
bool GameControllerSim::excluded(int team, int player) const { return robot(team, player).excluded; }
double GameControllerSim::penaltyLeft(int team, int player) const { return robot(team, player).left; }
int GameControllerSim::hardwarePenalties(int team, int player) const { return robot(team, player).hardware; }

void GameControllerSim::sync() {
  data_.secsRemaining = shown<std::int16_t>(remaining_);
  const double inState = now_ - since_;
  data_.secondaryTime = data_.state == gc::State::Ready ? shown<std::int16_t>(config_.readyLimit - inState)
                        : data_.state == gc::State::Set ? shown<std::int16_t>(config_.whistleDelay - inState)
                                                        : std::int16_t{0};
  for (std::size_t team = 0; team < 2; ++team)
    for (int p = 1; p <= config_.players; ++p) {
      const Robot& r = robots_[team][static_cast<std::size_t>(p - 1)];
      auto& info = data_.teams[team].players[static_cast<std::size_t>(p - 1)];
      info.penalty = static_cast<std::uint8_t>(r.penalty);
      info.secsTillUnpenalised = r.excluded || r.left < 0 ? 0 : shown<std::uint8_t>(r.left);
    }
}

std::array<std::uint8_t, gc::kPacketSize> GameControllerSim::packet() {
  sync();
  ++data_.packetNumber;  // wraps, as the protocol's u8 does
  return gc::serialize(data_);
}

bool GameControllerSim::packetDue(double t) {
  if (t - lastPacket_ < config_.packetPeriod - 1e-9) return false;
  lastPacket_ = t;
  return true;
}

}  // namespace nao::sim
