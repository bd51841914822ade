#pragma once
// Motion cadence: the LEDs. The chest shows the game state as the rules ask (chestColour in
// robot/nao/GameController.h); the other LEDs stay off.
#include "representations/infrastructure/GameState.h"
#include "robot/JointRequest.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class LedControl : public Module<LedControl, Requires<GameState>, Provides<LedRequest>> {
 public:
  explicit LedControl(const ModuleContext& = {}) {}

 private:
  void update() override;
};

}  // namespace nao::modules
