#pragma once
// The NAO backend's safety layer (robot/nao/Safety.h) as the robot program needs to know it,
// written by the app before each cycle; the simulator's runs: the default.
namespace nao {

struct SafetyState {
  // The user unstiffened the robot (head buttons): the next chest press stiffens it again and
  // is no game-state button press.
  bool userUnstiffened = false;
};

}  // namespace nao
