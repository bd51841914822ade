#pragma once
// Motion cadence: the calibration challenge's mode from the button gestures (ButtonState):
// chest + head front held 1 s starts calibration, chest + head rear evaluation, each a new
// modeId; a head tap counts towards the next task. The same on the simulator's touch sensors
// and on a NAO's (LoLA Touch).
#include "representations/infrastructure/ButtonState.h"
#include "representations/infrastructure/ChallengeMode.h"
#include "robot/Module.h"
#include "robot/Parameters.h"
#include "robot/SensorData.h"

namespace nao::modules {

class ChallengeModeProvider
    : public Module<ChallengeModeProvider, Requires<ButtonState, SensorFrame>, Provides<ChallengeMode>> {
 public:
  explicit ChallengeModeProvider(const ModuleContext& = {}) {}

 private:
  void update() override;
};

}  // namespace nao::modules
