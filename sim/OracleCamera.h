#pragma once
// The simulator's side of the fast percept mode (--percepts oracle): a camera image without
// pixels that carries what the camera truly shows (robot/OracleView.h), from the world's state
// and field model, with no rendering. What a robot hides (the own feet, the other robot) is
// left out (ray cast), as is paint that the image border cuts lengthwise.
#include "robot/CameraImage.h"
#include "robot/OracleView.h"

namespace nao::sim {

class World;

OracleView oracleView(const World& world, int robot, CameraId camera);
// The camera's size and no pixels, with oracleView attached (timestamp left to the backend).
CameraImage oracleImage(const World& world, int robot, CameraId camera);

}  // namespace nao::sim
