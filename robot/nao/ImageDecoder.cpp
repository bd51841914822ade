#include "robot/nao/ImageDecoder.h"

#include <fstream>
#include <iterator>
#include <memory>
#include <vector>

#include "robot/Error.h"

#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
#define STBI_MAX_DIMENSIONS 8192
#include <stb/stb_image.h>

namespace nao {

CameraImage decodeImageFile(const std::string& path, CameraId camera) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw Error(path, "cannot open");
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (bytes.empty() || bytes.size() > (1u << 30)) throw Error(path, "not a readable PNG or JPEG image (empty or huge)");
  int width = 0, height = 0, channels = 0;
  const std::unique_ptr<unsigned char, void (*)(void*)> rgb(
      stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()), &width, &height, &channels, 3), stbi_image_free);
  if (!rgb) throw Error(path, std::string("not a readable PNG or JPEG image: ") + stbi_failure_reason());
  if (width < 2) throw Error(path, "image narrower than 2 pixels");
  CameraImage image;
  image.camera = camera;
  image.width = width - width % 2;
  image.height = height;
  image.yuyv.resize(static_cast<std::size_t>(image.width) * height * 2);
  for (int r = 0; r < height; ++r) {
    const unsigned char* in = rgb.get() + static_cast<std::size_t>(r) * width * 3;
    std::uint8_t* out = image.yuyv.data() + static_cast<std::size_t>(r) * image.width * 2;
    for (int c = 0; c < image.width; c += 2, in += 6, out += 4) yuyvPairFromRgb(in, out);
  }
  return image;
}

}  // namespace nao
