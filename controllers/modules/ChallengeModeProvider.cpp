#include "controllers/modules/ChallengeModeProvider.h"

#include "robot/ModuleRegistry.h"

namespace nao::modules {

namespace {
NAO_DEBUG_CHANNEL(kChallenge, "challenge", "each start of a challenge mode and each head tap, with the mode's id");
}  // namespace

void ChallengeModeProvider::update() {
  ChallengeMode& mode = out<ChallengeMode>();
  const double time = in<SensorFrame>().time;
  for (ButtonEvent e : in<ButtonState>().events) {
    if (e == ButtonEvent::StartCalibration || e == ButtonEvent::StartCalibrationEvaluation) {
      mode.mode = e == ButtonEvent::StartCalibration ? ChallengeMode::Mode::Calibration : ChallengeMode::Mode::Evaluation;
      ++mode.modeId;
      mode.since = time;
      mode.headTaps = 0;
    } else if (e == ButtonEvent::HeadTap && mode.mode != ChallengeMode::Mode::None) {
      ++mode.headTaps;
    } else {
      continue;
    }
    debug(kChallenge, [&] {
      return nlohmann::json{{"mode", challengeModeName(mode.mode)}, {"mode_id", mode.modeId}, {"head_taps", mode.headTaps}};
    });
  }
}

NAO_REGISTER_MODULE(ChallengeModeProvider);

}  // namespace nao::modules
