#pragma once
// Inputs and outputs of the modeling (self-localization, ball model): plain structs, so that the
// classes in this folder can be wrapped as modules (requires -> update -> provides) unchanged.
// SI units throughout: metres, radians, seconds. "Robot frame": x forward, y left, on the
// ground, at the robot's origin; "field frame": the SPL's (origin at the centre, x towards the
// opponent goal, y left).
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "controllers/MotionRequest.h"
#include "perception/vision/VisionTypes.h"
#include "representations/modeling/BallModel.h"
#include "representations/modeling/RobotPose.h"

namespace nao {

// How uncertain one percept set is. A point percept at distance d (m) from the robot has the
// standard deviation sigmaBase + sigmaPerMetre * d in each direction; a line's angle has
// sigmaAngle + sigmaAnglePerMetre * d. The bottom camera's percepts are more precise than the
// top camera's, so each set carries its own.
struct PerceptUncertainty {
  double sigmaBase = 0.03;            // m
  double sigmaPerMetre = 0.04;        // m per m of distance
  double sigmaAngle = 0.04;           // rad
  double sigmaAnglePerMetre = 0.01;   // rad per m of distance
};

// The field percepts of one camera image, robot frame at the image's time.
struct FieldPercepts {
  double time = 0;  // s, the image's timestamp
  LinesPercept lines;
  PerceptUncertainty uncertainty;
  // The ground this image surely shows (perception/modeling/ViewRegion.h: convex, counter-
  // clockwise, robot frame): field lines predicted inside it and not seen count against a
  // hypothesis. Empty: no such negative information (an unprocessed image, a test).
  std::vector<Eigen::Vector2d> view;
};

// Everything the self-localization takes in one cognition cycle.
struct LocalizationInput {
  Pose2 odometryDelta;                // robot-frame motion since the last cycle (m, m, rad)
  std::vector<FieldPercepts> percepts;  // zero, one or two sets (top and bottom camera)
  double gyroZ = 0;                   // rad/s; field-feature resets are refused while |gyroZ| is high
};

// The robot-frame motion between two odometry readings (the inputs' Odometry::pose):
// from.inverse() * to, or nullopt when either is not finite.
std::optional<Pose2> odometryDelta(const Pose2& from, const Pose2& to);

// One ball measurement (robot frame).
struct BallObservation {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();                 // m
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity() * 0.0025;  // m^2
};

// Everything the ball model takes in one cognition cycle.
struct BallInput {
  double time = 0;                    // s, monotonic (the image's time)
  Pose2 odometryDelta;                // robot-frame motion since the last cycle
  std::vector<BallObservation> observations;  // this cycle's ball percepts (both cameras)
  bool ballExpectedInView = false;    // the model's ball lay inside a camera image this cycle
  std::optional<Pose2> robotPose;     // for the field-frame outputs, when localized
};

}  // namespace nao
