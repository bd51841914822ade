#pragma once
// The Autonomous Calibration Challenge's mode (../shared/reference/calibration-challenge.md):
// the referee starts phase 1 (calibration) by holding chest + head front for 1 s, phase 2
// (evaluation) by chest + head rear, and taps the head between phase 2's tasks.
// ChallengeModeProvider keeps it as a level in the motion cadence, where no button event is
// missed, and it crosses to cognition with the other motion state.
namespace nao {

struct ChallengeMode {
  enum class Mode { None, Calibration, Evaluation };
  Mode mode = Mode::None;
  int modeId = 0;     // counts the starts: a new id is a new start, even of the same mode
  double since = 0;   // s, backend clock, of the start
  int headTaps = 0;   // head taps since the start
};

inline const char* challengeModeName(ChallengeMode::Mode m) {
  switch (m) {
    case ChallengeMode::Mode::None: return "none";
    case ChallengeMode::Mode::Calibration: return "calibration";
    case ChallengeMode::Mode::Evaluation: return "evaluation";
  }
  return "?";
}

}  // namespace nao
