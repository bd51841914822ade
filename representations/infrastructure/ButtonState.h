#pragma once
// This cycle's head and chest buttons and the gestures they completed (ButtonInterface in
// robot/nao/GameController.h detects them from the Touch array).
#include <vector>

namespace nao {

// The buttons (Touch array), as the rules and the calibration challenge use them.
enum class ButtonEvent {
  ChestPress,                  // chest alone, pressed and released
  StartCalibration,            // chest + head front held >= 1 s
  StartCalibrationEvaluation,  // chest + head rear held >= 1 s
  Unstiffen,                   // all three head buttons held >= 1 s
  HeadTap,                     // one head button alone, pressed and released within 0.05-1 s (next task)
};
const char* buttonEventName(ButtonEvent e);

struct ButtonState {
  std::vector<ButtonEvent> events;  // this cycle's
  bool chest = false, headFront = false, headMiddle = false, headRear = false;
};

}  // namespace nao
