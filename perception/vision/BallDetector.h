#pragma once
// The ball: candidates are non-field runs on the scan lines whose length fits the ball's
// expected image size at that position; each is verified classically: rays from the
// candidate find the ball's outline against the field, a circle fitted to it must have the
// expected radius, the inside must show the black-and-white pattern (bright, grey, with
// dark patches, no field colour) and the surroundings must be mostly field. The position
// is where the centre's viewing ray meets the plane at ball-radius height. Obstacle boxes
// are not used: a ball often lies right in front of a robot (or the robot's own shoulder
// looms over it in the bottom camera), and the verifier tells a ball from a robot's parts.
#include <vector>

#include "perception/CameraModel.h"
#include "perception/vision/ColourTests.h"
#include "perception/vision/VisionTypes.h"

namespace nao::vision {

struct BallParams {
  double radius = 0.05;                      // m
  double minRadiusRatio = 0.9, maxRadiusRatio = 1.5;  // fitted / expected image radius
  double minOutline = 0.5;   // of the rays that stay in the image, those meeting the field on the circle
  int rays = 16;
  int maxCandidates = 80;  // verified per image, those with a dark part first
  double maxFieldInside = 0.15;  // fraction of field-coloured samples inside the ball
  double minDarkInside = 0.08, maxDarkInside = 0.85;  // fraction of the black patches (and self-shadow)
  double minContrast = 0.35;     // (bright - dark) / bright inside the ball
  double minFieldAround = 0.6;   // fraction of field-coloured samples on a ring around it
  double maxGreyness = 0.6;      // mean chroma inside / mean chroma of the field around
};

struct BallCandidate {
  Eigen::Vector2d seed = Eigen::Vector2d::Zero();
  double expectedRadius = 0;
  int priority = 0;  // 0: its run has a dark part (a black patch), 1: not
  bool alongVertical = true;  // found on a vertical scan line
  bool fitted = false;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius = 0;
  bool accepted = false;
  double score = 0;
  const char* rejectedBy = "";
  // The verifier's measurements (for debugging and tests).
  double contrast = 0, darkRatio = 0, fieldInside = 0, fieldAround = 0, bright = 0, yAround = 0, satInside = 0,
         satAround = 0;
  int inliers = 0;
  bool byBrightOutline = false;  // outlined by its bright parts (something other than field beside it)
};

// The best verified candidate; `candidates` (optional) receives all of them for debugging.
BallPercept detectBall(const CameraImage& image, const ScanLineRegions& regions, const FieldReference& field,
                       const ObstaclesPercept& obstacles,
                       const CameraMatrix& cm, const BallParams& params = {},
                       std::vector<BallCandidate>* candidates = nullptr);

// The image radius a ball at this pixel would have (0 above the horizon).
double expectedBallRadius(const CameraMatrix& cm, const Eigen::Vector2d& pixel, double radius);

}  // namespace nao::vision
