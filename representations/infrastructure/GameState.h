#pragma once
// The robot's view of the game: the GameController's state as far as it concerns this robot,
// or what the chest button set without one (robot/nao/GameController.h fills it; in the
// simulator the scenario's GameController). Modeling uses it for the game situation (where a
// robot enters, where a penalised one returns), behaviour for what to do.
#include <cstdint>

namespace nao::gc {

enum class State : std::uint8_t { Initial = 0, Ready = 1, Set = 2, Playing = 3, Finished = 4, Standby = 5 };
enum class GamePhase : std::uint8_t { Normal = 0, PenaltyShootout = 1, Overtime = 2, Timeout = 3 };
enum class SetPlay : std::uint8_t { None = 0, GoalKick = 1, PushingFreeKick = 2, CornerKick = 3, KickIn = 4, PenaltyKick = 5 };
enum class Penalty : std::uint8_t {
  None = 0, IllegalBallContact = 1, PlayerPushing = 2, IllegalMotionInSet = 3, InactivePlayer = 4,
  IllegalPosition = 5, LeavingTheField = 6, RequestForPickup = 7, LocalGameStuck = 8,
  IllegalPositionInSet = 9, PlayerStance = 10, IllegalMotionInStandby = 11, Substitute = 14, Manual = 15
};

}  // namespace nao::gc

namespace nao {

// The robot's view of the game.
struct GameState {
  gc::State state = gc::State::Initial;
  gc::GamePhase gamePhase = gc::GamePhase::Normal;
  gc::SetPlay setPlay = gc::SetPlay::None;
  gc::Penalty penalty = gc::Penalty::None;  // this robot's
  int secsTillUnpenalised = 0;
  bool firstHalf = true;
  bool ownKickOff = false;  // kickingTeam == own team
  int secsRemaining = 0, secondaryTime = 0;
  int ownScore = 0, opponentScore = 0;
  int teamNumber = 0, playerNumber = 1;
  int fieldPlayerColour = 0;
  bool goalkeeper = false;
  bool fromGameController = false;  // false: set by the buttons
  double lastPacketTime = -1;        // backend time of the last accepted packet
  std::uint8_t packetNumber = 0;

  bool penalised() const { return penalty != gc::Penalty::None; }
};

}  // namespace nao
