#pragma once
// Motion cadence: the robot's GameState. While the GameController's packets arrive it decides;
// without it the chest button plays its part of the rules (pressChestButton in
// robot/nao/GameController.h), starting from the last state the GameController set.
#include "representations/infrastructure/ButtonState.h"
#include "representations/infrastructure/GameControllerData.h"
#include "representations/infrastructure/GameState.h"
#include "representations/infrastructure/SafetyState.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class GameStateProvider : public Module<GameStateProvider, Requires<GameControllerData, ButtonState, SafetyState>,
                                        Provides<GameState>> {
 public:
  explicit GameStateProvider(const ModuleContext& = {}) {}

 private:
  void update() override;

  GameState state_;
};

}  // namespace nao::modules
