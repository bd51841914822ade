#include "sim/ImageIO.h"

#include <algorithm>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include <jpeglib.h>
#include <zlib.h>

// stb's decoder and encoder, private to this file (the robot program's ImageDecoder has its own).
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_BMP
#define STBI_ONLY_PNM
#define STBI_NO_STDIO
#define STBI_MAX_DIMENSIONS 8192
#include <stb/stb_image.h>
namespace {
// PNG's deflate by zlib at its fastest level (as imgcodecs wrote them): stb's own is slower.
unsigned char* zlibCompress(unsigned char* data, int size, int* outSize, int /*quality*/) {
  uLongf bound = compressBound(static_cast<uLong>(size));
  auto* out = static_cast<unsigned char*>(std::malloc(bound));
  if (!out || compress2(out, &bound, data, static_cast<uLong>(size), Z_BEST_SPEED) != Z_OK) {
    std::free(out);
    return nullptr;
  }
  *outSize = static_cast<int>(bound);
  return out;
}
}  // namespace
#define STBIW_ZLIB_COMPRESS zlibCompress
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>

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

// JPEG through libjpeg(-turbo), as OpenCV's imgcodecs decoded it (the same pixels, checked on the
// real goal-box images), without loading imgcodecs and the 140 libraries it links (GDAL and
// company: a quarter second at every process start). Errors jump back here instead of exiting;
// the first warning ("Corrupt JPEG data: ...") goes into the error should the decode fail.
struct JpegErrors {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  std::string message;
};

void jpegFailed(j_common_ptr info) {
  auto* errors = reinterpret_cast<JpegErrors*>(info->err);
  char text[JMSG_LENGTH_MAX] = "";
  info->err->format_message(info, text);
  errors->message = text;
  std::longjmp(errors->jump, 1);
}

void jpegWarning(j_common_ptr info, int level) {
  auto* errors = reinterpret_cast<JpegErrors*>(info->err);
  if (level >= 0 || !errors->message.empty()) return;  // trace messages, or not the first warning
  char text[JMSG_LENGTH_MAX] = "";
  info->err->format_message(info, text);
  errors->message = text;
}

// RGB rows, or empty with `why` set.
cv::Mat decodeJpeg(const std::vector<std::uint8_t>& bytes, std::string& why) {
  jpeg_decompress_struct info{};
  JpegErrors errors;
  info.err = jpeg_std_error(&errors.manager);
  errors.manager.error_exit = jpegFailed;
  errors.manager.emit_message = jpegWarning;
  cv::Mat rgb;  // constructed before the jump point: longjmp skips no destructor of it
  if (setjmp(errors.jump)) {
    jpeg_destroy_decompress(&info);
    why = errors.message;
    return cv::Mat();
  }
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, bytes.data(), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&info, TRUE);
  info.out_color_space = JCS_RGB;
  jpeg_start_decompress(&info);
  if (info.output_width > 8192 || info.output_height > 8192) {
    jpeg_destroy_decompress(&info);
    why = "larger than 8192 pixels";
    return cv::Mat();
  }
  rgb.create(static_cast<int>(info.output_height), static_cast<int>(info.output_width), CV_8UC3);
  while (info.output_scanline < info.output_height) {
    JSAMPROW row = rgb.ptr<std::uint8_t>(static_cast<int>(info.output_scanline));
    jpeg_read_scanlines(&info, &row, 1);
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  return rgb;
}

// PNG (and BMP, PNM) through stb_image: lossless, the same pixels as imgcodecs gave.
cv::Mat decodeOther(const std::vector<std::uint8_t>& bytes, std::string& why) {
  if (bytes.size() > (1u << 30)) {
    why = "larger than 1 GiB";
    return cv::Mat();
  }
  int width = 0, height = 0, channels = 0;
  stbi_uc* pixels = stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()), &width, &height, &channels, 3);
  if (!pixels) {
    why = stbi_failure_reason();
    return cv::Mat();
  }
  cv::Mat rgb = cv::Mat(height, width, CV_8UC3, pixels).clone();
  stbi_image_free(pixels);
  return rgb;
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
  const cv::Mat packed = rgb.isContinuous() ? rgb : rgb.clone();
  // Always PNG, whatever the file name says (stb_image_write's filters, zlib's deflate).
  std::string encoded;
  const auto append = [](void* to, void* data, int size) { static_cast<std::string*>(to)->append(static_cast<const char*>(data), static_cast<std::size_t>(size)); };
  if (!stbi_write_png_to_func(append, &encoded, packed.cols, packed.rows, 3, packed.data, packed.cols * 3))
    throw Error(path, "cannot encode PNG");
  io::writeFile(path, encoded);
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
  std::string why;
  const bool jpeg = bytes.size() >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff;
  cv::Mat rgb = jpeg ? decodeJpeg(bytes, why) : decodeOther(bytes, why);
  if (rgb.empty() || rgb.cols < 2 || rgb.rows < 1)
    throw Error(path, "not a readable PNG or JPEG image (corrupt or truncated?)" + (why.empty() ? std::string() : ": " + why));
  if (rgb.cols % 2 != 0) rgb = rgb.colRange(0, rgb.cols - 1).clone();
  return cameraImageFromRgb(rgb, camera, 0);
}

}  // namespace nao::sim
