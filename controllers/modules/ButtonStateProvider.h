#pragma once
// Motion cadence: the head and chest buttons and their gestures from the Touch array
// (ButtonInterface in robot/nao/GameController.h: presses, holds, combinations).
#include "representations/infrastructure/ButtonState.h"
#include "robot/Module.h"
#include "robot/Parameters.h"
#include "robot/SensorData.h"
#include "robot/nao/GameController.h"

namespace nao::modules {

class ButtonStateProvider : public Module<ButtonStateProvider, Requires<SensorFrame>, Provides<ButtonState>> {
 public:
  explicit ButtonStateProvider(const ModuleContext& = {}) {}

 private:
  void update() override;

  ButtonInterface buttons_;
};

}  // namespace nao::modules
