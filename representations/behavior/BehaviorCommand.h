#pragma once
// What the robot's operator asks of the behaviour (the command line's `run --goto`): an input
// the app writes on the motion side, copied to cognition with the declared exchange.
#include <optional>

#include "robot/math/Pose2.h"

namespace nao {

struct BehaviorCommand {
  std::optional<Pose2> goTo;  // walk to this field pose (m, m, rad) by the self-localization
};

}  // namespace nao
