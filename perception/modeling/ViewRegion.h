#pragma once
// The ground an image surely shows: negative information for the self-localization. A field
// line a hypothesis puts inside this region should have been seen; a hypothesis that keeps
// predicting lines where the images show none is wrong (a kidnapped robot's old pose, which
// otherwise still fits the one line it sees). docs/modeling.md.
#include <vector>

#include <Eigen/Core>

#include "perception/CameraModel.h"

namespace nao {

// The image (less `margin` of its width and height on each side) projected onto the ground,
// robot frame, cut at `maxDistance` m from the robot along each viewing direction: a convex
// polygon, counter-clockwise; empty when the camera does not see the ground.
std::vector<Eigen::Vector2d> groundView(const CameraMatrix& camera, double maxDistance, double margin);

// The length of the segment a-b inside the convex counter-clockwise polygon (0 for an empty one).
double lengthInside(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const std::vector<Eigen::Vector2d>& polygon);

}  // namespace nao
