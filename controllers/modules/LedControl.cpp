#include "controllers/modules/LedControl.h"

#include "robot/ModuleRegistry.h"
#include "robot/nao/GameController.h"

namespace nao::modules {

void LedControl::update() {
  LedRequest& leds = out<LedRequest>();
  leds = LedRequest{};
  leds.chest = chestColour(in<GameState>());
}

NAO_REGISTER_MODULE(LedControl);

}  // namespace nao::modules
