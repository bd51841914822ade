#pragma once
// Whether the robot is falling or lies (FallDetector provides it).

namespace nao {

enum class FallDirection { None, Front, Back, Left, Right };

inline const char* fallDirectionName(FallDirection d) {
  switch (d) {
    case FallDirection::Front: return "front";
    case FallDirection::Back: return "back";
    case FallDirection::Left: return "left";
    case FallDirection::Right: return "right";
    case FallDirection::None: break;
  }
  return "none";
}

struct FallState {
  bool falling = false;  // tipping over, not yet down
  bool fallen = false;   // down (latched until upright again)
  FallDirection direction = FallDirection::None;
  double fallTime = -1;  // frame time at which `fallen` became true; -1 when not fallen
};

}  // namespace nao
