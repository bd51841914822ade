#pragma once
// The image files --cameras files:DIR replays, decoded without the simulator's libraries:
// PNG and JPEG by stb_image (header-only, Debian's libstb-dev), so the robot executable takes
// the same files as nao-soccer and both turn them into the same frames.
#include <string>

#include "robot/CameraImage.h"

namespace nao {

// The file as a YUYV frame of `camera` (an odd width loses its last column: YUYV comes in
// pairs). Throws nao::Error(path, ...) for a file that cannot be read or decoded.
CameraImage decodeImageFile(const std::string& path, CameraId camera);

}  // namespace nao
