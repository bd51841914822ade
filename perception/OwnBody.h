#pragma once
// The robot's own body as its cameras see it (B-Human's body contour, here in 3D): the limbs
// as capsules, the torso and the feet as boxes, in the robot frame at an image's exposure
// time, from the joint angles. The
// vision refuses a ball whose centre's viewing ray meets one of them: looking down, the
// bottom camera sees the robot's own feet, shins and hands, round, white and grey, and a
// ball found there three images in a row would become the ball model's ball.
//
// The radii are a real NAO's shells (config/parameters/OwnBodyProvider.json), wider than the
// simulated robot's capsules: hiding a little too much of the image costs a ball touching
// the body, taking a hand for the ball costs the game.
#include <vector>

#include <Eigen/Geometry>

#include "perception/CameraModel.h"
#include "robot/JointIds.h"

namespace nao {

struct OwnBody {
  struct Capsule {
    Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();  // robot frame, m
    double radius = 0;                                                          // m
  };
  struct Box {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // the box's centre and axes, robot frame
    Eigen::Vector3d halfSize = Eigen::Vector3d::Zero();       // m
  };
  std::vector<Capsule> parts;  // both empty: not known for this image, nothing is hidden
  std::vector<Box> boxes;

  // Whether the viewing ray of `pixel` (in front of the camera) passes through a part.
  bool hides(const CameraMatrix& cm, const Eigen::Vector2d& pixel) const;
};

struct OwnBodyParams {
  double shoulder = 0.035;// sphere about the shoulder joint
  double upperArm = 0.032;  // shoulder to elbow
  double lowerArm = 0.03;  // elbow to the hand point
  double thigh = 0.045;      // hip to knee
  double tibia = 0.04;     // knee to ankle
  double footHeight = 0.065;  // the foot's box: the sole rectangle this high ...
  double footMargin = 0.01;   // ... and this much bigger on every side
  double torsoHalfX = 0.05, torsoHalfY = 0.065, torsoHalfZ = 0.085;  // the torso box about (-0.005, 0, 0.115)
};

// The parts at these joint angles; robotToTorso places the torso in the robot frame (with the
// calibrated body offset, as the camera matrix does).
OwnBody ownBodyAt(const JointArray& joints, const Eigen::Isometry3d& robotToTorso, const OwnBodyParams& params);

// Squared distance between the ray o + t d (t >= 0) and the segment a b.
double raySegmentDistanceSquared(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& a,
                                 const Eigen::Vector3d& b);
// Whether the ray o + t d (t >= 0) meets the box.
bool rayMeetsBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const OwnBody::Box& box);

template <class V>
void describe(V& v, OwnBodyParams& p) {
  v("shoulder", p.shoulder, 0.0, 0.2);
  v("upperArm", p.upperArm, 0.0, 0.2);
  v("lowerArm", p.lowerArm, 0.0, 0.2);
  v("thigh", p.thigh, 0.0, 0.2);
  v("tibia", p.tibia, 0.0, 0.2);
  v("footHeight", p.footHeight, 0.0, 0.2);
  v("footMargin", p.footMargin, 0.0, 0.1);
  v("torsoHalfX", p.torsoHalfX, 0.0, 0.2);
  v("torsoHalfY", p.torsoHalfY, 0.0, 0.2);
  v("torsoHalfZ", p.torsoHalfZ, 0.0, 0.2);
}

}  // namespace nao
