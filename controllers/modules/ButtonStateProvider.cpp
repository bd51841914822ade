#include "controllers/modules/ButtonStateProvider.h"

#include "robot/ModuleRegistry.h"

namespace nao::modules {

void ButtonStateProvider::update() {
  const SensorFrame& frame = in<SensorFrame>();
  out<ButtonState>() = buttons_.update(frame.touch, frame.time);
}

NAO_REGISTER_MODULE(ButtonStateProvider);

}  // namespace nao::modules
