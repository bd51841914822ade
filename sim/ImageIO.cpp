#include "sim/ImageIO.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "robot/Error.h"
#include "robot/OutputFiles.h"

namespace nao::sim {

namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::vector<std::uint8_t> readBytes(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error(path, "file not found");
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(path, "not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open file");
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw Error(path, "cannot read file");
  return bytes;
}

// Whether the last `window` bytes contain `marker` (a file's end marker, maybe followed by padding).
bool endsWithin(const std::vector<std::uint8_t>& bytes, std::initializer_list<std::uint8_t> marker,
                std::size_t window) {
  const auto from = bytes.end() - static_cast<std::ptrdiff_t>(std::min(window, bytes.size()));
  return std::search(from, bytes.end(), marker.begin(), marker.end()) != bytes.end();
}

// Truncated PNG/JPEG files would decode partially (libjpeg fills the rest grey): refuse them.
void checkComplete(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  static const std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
  if (bytes.size() >= png.size() && std::equal(png.begin(), png.end(), bytes.begin()) &&
      !endsWithin(bytes, {'I', 'E', 'N', 'D'}, 64))
    throw Error(path, "truncated PNG (no IEND chunk at the end)");
  if (bytes.size() >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff &&
      !endsWithin(bytes, {0xff, 0xd9}, 4096))
    throw Error(path, "truncated JPEG (no end-of-image marker)");
}

// libpng and libjpeg print their own warnings on stderr ("libpng warning: iCCP: ...", "Corrupt
// JPEG data: ..."). Decoding with stderr caught keeps one image to at most one line: dropped when
// the image decodes, folded into the error when it does not.
cv::Mat decodeQuietly(const std::vector<std::uint8_t>& bytes, std::string& printed) {
  std::fflush(stderr);
  std::FILE* sink = std::tmpfile();
  const int saved = sink ? ::dup(2) : -1;
  if (saved >= 0) ::dup2(::fileno(sink), 2);
  cv::Mat bgr;
  std::string exception;
  try {
    bgr = cv::imdecode(bytes, cv::IMREAD_COLOR);
  } catch (const cv::Exception& e) {
    exception = e.err;
  }
  if (saved >= 0) {
    std::fflush(stderr);
    ::dup2(saved, 2);
    ::close(saved);
    std::rewind(sink);
    char line[256] = "";
    if (std::fgets(line, sizeof line, sink)) printed = line;
    while (!printed.empty() && (printed.back() == '\n' || printed.back() == '\r')) printed.pop_back();
  }
  if (sink) std::fclose(sink);
  if (!exception.empty()) printed = exception + (printed.empty() ? "" : "; " + printed);
  return bgr;
}

}  // namespace

cv::Mat yuyvFromRgb(const cv::Mat& rgb) {
  if (rgb.type() != CV_8UC3 || rgb.cols % 2 != 0)
    throw Error("yuyvFromRgb", "need an 8-bit 3-channel image of even width");
  cv::Mat out(rgb.rows, rgb.cols, CV_8UC2);
  for (int r = 0; r < rgb.rows; ++r) {
    const std::uint8_t* in = rgb.ptr<std::uint8_t>(r);
    std::uint8_t* o = out.ptr<std::uint8_t>(r);
    for (int c = 0; c < rgb.cols; c += 2, in += 6, o += 4) yuyvPairFromRgb(in, o);
  }
  return out;
}

cv::Mat rgbFromYuyv(const cv::Mat& yuyv) {
  if (yuyv.type() != CV_8UC2 || yuyv.cols % 2 != 0)
    throw Error("rgbFromYuyv", "need a 2-channel YUYV image of even width");
  cv::Mat out(yuyv.rows, yuyv.cols, CV_8UC3);
  for (int r = 0; r < yuyv.rows; ++r) {
    const std::uint8_t* in = yuyv.ptr<std::uint8_t>(r);
    std::uint8_t* o = out.ptr<std::uint8_t>(r);
    for (int c = 0; c < yuyv.cols; c += 2, in += 4, o += 6) {
      const double u = in[1] - 128.0, v = in[3] - 128.0;
      for (int k = 0; k < 2; ++k) {
        const double y = in[2 * k];
        o[3 * k + 0] = roundToByte(y + 1.402 * v);
        o[3 * k + 1] = roundToByte(y - 0.344136 * u - 0.714136 * v);
        o[3 * k + 2] = roundToByte(y + 1.772 * u);
      }
    }
  }
  return out;
}

CameraImage cameraImageFromRgb(const cv::Mat& rgb, CameraId camera, double timestamp) {
  const cv::Mat yuyv = yuyvFromRgb(rgb);
  CameraImage image;
  image.camera = camera;
  image.width = rgb.cols;
  image.height = rgb.rows;
  image.timestamp = timestamp;
  image.yuyv.resize(static_cast<std::size_t>(rgb.cols) * rgb.rows * 2);
  for (int r = 0; r < yuyv.rows; ++r)
    std::copy_n(yuyv.ptr<std::uint8_t>(r), rgb.cols * 2,
                image.yuyv.data() + static_cast<std::size_t>(r) * rgb.cols * 2);
  return image;
}

cv::Mat rgbFromCameraImage(const CameraImage& image) {
  if (!image.valid()) throw Error("rgbFromCameraImage", "invalid camera image");
  // The wrapper does not own the bytes; rgbFromYuyv copies.
  const cv::Mat yuyv(image.height, image.width, CV_8UC2, const_cast<std::uint8_t*>(image.yuyv.data()));
  return rgbFromYuyv(yuyv);
}

void writePng(const std::string& path, const cv::Mat& rgb) {
  if (rgb.empty() || rgb.type() != CV_8UC3) throw Error(path, "not an 8-bit RGB image");
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  // Always PNG, whatever the file name says.
  std::vector<std::uint8_t> encoded;
  try {
    if (!cv::imencode(".png", bgr, encoded)) throw Error(path, "cannot encode PNG");
  } catch (const cv::Exception& e) {
    throw Error(path, std::string("cannot encode PNG: ") + e.err);
  }
  io::writeFile(path, std::string_view(reinterpret_cast<const char*>(encoded.data()), encoded.size()));
}

void writePng(const std::string& path, const CameraImage& image) {
  if (!image.valid()) throw Error(path, "invalid camera image (size does not match its data)");
  writePng(path, rgbFromCameraImage(image));
}

CameraImage readImage(const std::string& path, int width, int height, CameraId camera) {
  const std::vector<std::uint8_t> bytes = readBytes(path);
  if (bytes.empty()) throw Error(path, "empty file");
  const std::string ext = lowerExtension(path);
  if (ext == ".yuv" || ext == ".yuyv" || ext == ".raw") {
    if (width == 0 && height == 0) {
      for (auto [w, h] : {std::pair{1280, 960}, {640, 480}, {320, 240}})
        if (bytes.size() == static_cast<std::size_t>(w) * h * 2) width = w, height = h;
      if (width == 0)
        throw Error(path, "raw YUYV of " + std::to_string(bytes.size()) + " bytes: give its size (--size WxH)");
    }
    if (width <= 0 || height <= 0 || width % 2 != 0 || width > 8192 || height > 8192)
      throw Error(path, "raw YUYV size " + std::to_string(width) + "x" + std::to_string(height) +
                            ": must be positive with an even width");
    const std::size_t expected = static_cast<std::size_t>(width) * height * 2;
    if (bytes.size() != expected)
      throw Error(path, "raw YUYV " + std::to_string(width) + "x" + std::to_string(height) + " needs " +
                            std::to_string(expected) + " bytes, the file has " + std::to_string(bytes.size()));
    CameraImage image;
    image.camera = camera;
    image.width = width;
    image.height = height;
    image.yuyv = bytes;
    return image;
  }
  checkComplete(path, bytes);
  std::string printed;
  cv::Mat bgr = decodeQuietly(bytes, printed);
  if (bgr.empty() || bgr.cols < 2 || bgr.rows < 1)
    throw Error(path, "not a readable PNG or JPEG image (corrupt or truncated?)" +
                          (printed.empty() ? std::string() : ": " + printed));
  if (bgr.cols % 2 != 0) bgr = bgr.colRange(0, bgr.cols - 1).clone();
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  return cameraImageFromRgb(rgb, camera, 0);
}

}  // namespace nao::sim
