#pragma once
// The centre circle: chains of line spots that bend like an arc of the known radius on the
// ground give centre hypotheses; the best-supported centre is refined by least squares over
// every spot on its ring and accepted when the spots cover enough of the arc and the ring
// passes the white test where it is in view.
#include <vector>

#include "perception/CameraModel.h"
#include "perception/vision/LineDetector.h"
#include "perception/vision/VisionTypes.h"

namespace nao::vision {

struct CircleParams {
  double radius = 0.75;     // m, to the line centre (FieldModel::centerCircleRadius)
  double lineWidth = 0.05;  // m
  int minSpots = 8;
  double minArcDeg = 60;    // angular extent the spots must cover (in 10 deg bins)
  double whiteRatio = 0.6;  // of the ring's white-test pairs in view
  int minRingSamples = 8;   // ring samples in view for the white test to count
};

// onCircle (optional): set to 1 for every spot that lies on the found circle.
LinesPercept::Circle detectCircle(const LineCandidates& candidates, const CameraImage& image,
                                  const FieldReference& field, const ObstaclesPercept& obstacles,
                                  const CameraMatrix& cm, const CircleParams& params = {},
                                  std::vector<char>* onCircle = nullptr);

// Least-squares centre of a circle of known radius through weighted points (Gauss-Newton
// from `initial`).
Eigen::Vector2d fitCircleCentre(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& sigma,
                                Eigen::Vector2d initial, double radius, int iterations = 6);

// Do these ground points (with their errors) bend like an arc of the given radius rather than
// lie on a straight line? A short piece of the centre circle passes for a line in the image.
bool looksLikeArc(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& sigma, double radius);

// The ground position error of a spot at `ground` (robot frame) for a given pixel error:
// grows with the square of the distance.
double groundSigma(const CameraMatrix& cm, const Eigen::Vector2d& ground, double pixelSigma = 0.7);

}  // namespace nao::vision
