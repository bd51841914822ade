#pragma once
// Where the ball is and where it goes (BallLocator provides it).
#include <Eigen/Core>

namespace nao {

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
