#pragma once
// What a simulated camera truly shows, for the fast percept mode (--percepts oracle): the
// simulator hands it over with an image that has no pixels, and the OracleVision module turns
// it into percepts with the errors the real vision makes. Everything is where the TRUE camera
// sees it (pixels, as a perfect detector would find them); the module projects the pixels with
// the robot's own camera matrix, as the vision does. Never present on a NAO.
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace nao {

struct OracleView {
  // Distances are on the ground from the camera's foot point (m).
  struct Line {
    Eigen::Vector2d imageFrom, imageTo;  // the visible stretch of the line's centre
    double length = 0;                   // of the visible stretch, m
    double distance = 0;                 // of its nearest point
  };
  struct Ball {
    Eigen::Vector2d image;  // centre pixel
    double radiusPx = 0;
    double distance = 0;
    double inImage = 0;  // share of the ball's disc inside the image, 0..1
  };
  struct Spot {
    Eigen::Vector2d image;  // pixel of a ground point (circle centre, penalty cross)
    double distance = 0;
  };
  std::vector<Line> lines;
  std::vector<Ball> balls;
  std::optional<Spot> circleCentre;  // the centre circle with at least half of it in view
  std::optional<Spot> penaltyMark;   // a cross wholly in the image
};

}  // namespace nao
