#include "controllers/modules/GameStateProvider.h"

#include "robot/ModuleRegistry.h"
#include "robot/nao/GameController.h"

namespace nao::modules {

void GameStateProvider::update() {
  const GameControllerData& gc = in<GameControllerData>();
  if (gc.active) {
    state_ = gc.state;  // the chest button is ignored: the GameController decides
  } else {
    state_.teamNumber = gc.state.teamNumber;
    state_.playerNumber = gc.state.playerNumber;
    for (ButtonEvent e : in<ButtonState>().events)
      if (e == ButtonEvent::ChestPress && !in<SafetyState>().userUnstiffened) pressChestButton(state_);
  }
  out<GameState>() = state_;
}

NAO_REGISTER_MODULE(GameStateProvider);

}  // namespace nao::modules
