#pragma once
// What the GameController last told this robot, as the app's UDP receiver (robot/nao/
// GameController.h: packets checked, this team's and player's part taken) keeps it; the app
// writes it before each cycle. The simulator's runs have none: the default (not active).
// GameStateProvider makes the robot's GameState from it and the chest button.
#include "representations/infrastructure/GameState.h"

namespace nao {

struct GameControllerData {
  bool active = false;  // this team's packets arrive (the last within the receiver's time-out)
  GameState state;      // as the packets set it; team and player numbers even while not active
};

}  // namespace nao
