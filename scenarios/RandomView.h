#pragma once
// A random observer for the vision's evaluations and its training: anywhere on the field,
// facing anywhere, the head anywhere in its usual range, small camera offsets. Both users draw
// from rng through this one function, so a seed gives them the same scenes. The pose is drawn
// theta, y, x: the order GCC evaluated the constructor's arguments in when the committed
// figures and ball model were made (C++ leaves it to the compiler; now every compiler agrees).
#include <array>
#include <cmath>
#include <random>

#include <Eigen/Core>

#include "controllers/StandController.h"
#include "perception/CameraCalibration.h"
#include "perception/FieldDimensions.h"
#include "robot/JointIds.h"

namespace nao::sim {

struct RandomView {
  Eigen::Vector3d pose;  // field frame (x, y, theta)
  JointArray posture;    // standing, the head turned
  CameraCalibration offsets;
};

inline RandomView randomView(const FieldModel& field, double maxOffsetDeg, std::mt19937_64& rng) {
  constexpr double kDeg = M_PI / 180;
  std::uniform_real_distribution<double> uni(0, 1);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * uni(rng); };
  RandomView v;
  const double theta = uniform(-M_PI, M_PI), y = uniform(-field.halfWidth(), field.halfWidth());
  v.pose = Eigen::Vector3d(uniform(-field.halfLength(), field.halfLength()), y, theta);
  v.posture = StandController::standPosture();
  v.posture[HeadYaw] = uniform(-100, 100) * kDeg;
  v.posture[HeadPitch] = uniform(-15, 25) * kDeg;
  std::array<double, 6> off{};
  for (double& o : off) o = uniform(-maxOffsetDeg, maxOffsetDeg) * kDeg;
  v.offsets = CameraCalibration::fromArray(off);
  return v;
}

}  // namespace nao::sim
