#pragma once
// Moved to representations/ (one representation per header) and robot/math/Pose2.h; this
// header only forwards for code that still includes it. New code includes those directly.
#include "representations/behavior/MotionRequest.h"
#include "representations/motion/MotionInfo.h"
#include "representations/motion/Odometry.h"
#include "robot/math/Pose2.h"
