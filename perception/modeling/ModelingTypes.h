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
};

// Everything the self-localization takes in one cognition cycle.
struct LocalizationInput {
  Pose2 odometryDelta;                // robot-frame motion since the last cycle (m, m, rad)
  std::vector<FieldPercepts> percepts;  // zero, one or two sets (top and bottom camera)
  double gyroZ = 0;                   // rad/s; field-feature resets are refused while |gyroZ| is high
};

// The self-localization's result.
struct RobotPose {
  Pose2 pose;                                                // the robot in the field frame
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();  // of (x m, y m, theta rad)
  double quality = 0;  // 0..1: the best hypothesis' recent share of percepts that fitted
  bool valid = false;  // quality and covariance good enough to act on
  int hypotheses = 0;  // how many hypotheses the filter keeps
  double sigmaTranslation() const;  // m, sqrt of the largest eigenvalue of the xy block
  double sigmaRotation() const;     // rad
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

// The ball model's result. Robot frame unless named field*.
struct BallModel {
  bool valid = false;   // a ball has been seen since the last reset
  bool lost = false;    // not seen in `lostAfterFrames` cycles in which it should have been
  bool rolling = false; // the rolling hypothesis is selected
  Eigen::Vector2d position = Eigen::Vector2d::Zero();     // m
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();     // m/s
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Identity();  // of (x, y, vx, vy)
  Eigen::Vector2d endPosition = Eigen::Vector2d::Zero();  // where it stops (constant deceleration)
  double seenTime = -1;  // s, time of the last percept used
  int unseenFrames = 0;  // consecutive cycles it should have been seen and was not
  bool fieldValid = false;  // the field-frame values below are set (a robot pose was given)
  Eigen::Vector2d fieldPosition = Eigen::Vector2d::Zero();
  Eigen::Vector2d fieldVelocity = Eigen::Vector2d::Zero();
  Eigen::Vector2d fieldEndPosition = Eigen::Vector2d::Zero();
};

}  // namespace nao
