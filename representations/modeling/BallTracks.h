#pragma once
// The balls the robot knows on the field (BallTracker provides it). A 1vs1 game has four, and
// the player chooses among them; the ball model (BallModel) follows one at a time. Field frame
// of the robot's own side (it attacks +x).
#include <vector>

#include <Eigen/Core>

namespace nao {

struct BallTracks {
  struct Track {
    int id = 0;
    Eigen::Vector2d position = Eigen::Vector2d::Zero();  // field, m
    double lastSeen = -1;  // s, exposure of the newest percept it took (-1: only expected, never seen)
    int sightings = 0;     // percepts it took
    int misses = 0;        // images since then in which it should have been seen and was not
  };
  std::vector<Track> tracks;
};

}  // namespace nao
