// decodeImageFile (robot/nao/ImageDecoder, stb_image): what --cameras files:DIR feeds both
// executables. A PNG decodes to exactly the frame the simulator makes of the same pixels; a
// JPEG to nearly it; an odd width loses its last column; a file that is not an image, cut
// short or missing is one error naming the file.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "robot/Error.h"
#include "robot/nao/ImageDecoder.h"
#include "sim/ImageIO.h"

namespace nao {
namespace {

namespace fs = std::filesystem;

fs::path dir() {
  const fs::path d = fs::path(::testing::TempDir()) / "image_decoder_test";
  fs::create_directories(d);
  return d;
}

cv::Mat noiseImage(int width, int height) {
  cv::Mat rgb(height, width, CV_8UC3);
  std::mt19937 rng(7);
  for (int r = 0; r < height; ++r)
    for (int c = 0; c < width * 3; ++c) rgb.ptr<std::uint8_t>(r)[c] = static_cast<std::uint8_t>(rng() & 0xff);
  cv::GaussianBlur(rgb, rgb, cv::Size(5, 5), 1.5);  // JPEG-friendly, still every value different
  return rgb;
}

std::string writeBgr(const std::string& name, const cv::Mat& rgb) {
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  const std::string path = (dir() / name).string();
  EXPECT_TRUE(cv::imwrite(path, bgr));
  return path;
}

void expectError(const std::string& path, const std::string& what) {
  try {
    decodeImageFile(path, CameraId::Top);
    FAIL() << path << " decoded";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(ImageDecoder, APngIsTheSimulatorsFrameOfTheSamePixels) {
  const cv::Mat rgb = noiseImage(64, 48);
  const CameraImage decoded = decodeImageFile(writeBgr("a.png", rgb), CameraId::Bottom);
  const CameraImage expected = sim::cameraImageFromRgb(rgb, CameraId::Bottom);
  EXPECT_EQ(decoded.camera, CameraId::Bottom);
  EXPECT_EQ(decoded.width, 64);
  EXPECT_EQ(decoded.height, 48);
  ASSERT_TRUE(decoded.valid());
  EXPECT_EQ(decoded.yuyv, expected.yuyv);
}

TEST(ImageDecoder, AJpegIsCloseAndAnOddWidthLosesItsLastColumn) {
  const cv::Mat rgb = noiseImage(65, 40);
  const CameraImage decoded = decodeImageFile(writeBgr("b.jpg", rgb), CameraId::Top);
  EXPECT_EQ(decoded.width, 64);
  EXPECT_EQ(decoded.height, 40);
  ASSERT_TRUE(decoded.valid());
  const CameraImage expected = sim::cameraImageFromRgb(rgb.colRange(0, 64).clone(), CameraId::Top);
  double sum = 0;
  for (std::size_t i = 0; i < decoded.yuyv.size(); ++i) sum += std::abs(decoded.yuyv[i] - expected.yuyv[i]);
  EXPECT_LT(sum / static_cast<double>(decoded.yuyv.size()), 4.0) << "JPEG's loss only";
}

TEST(ImageDecoder, BrokenFilesAreOneErrorNamingTheFile) {
  const std::string png = writeBgr("c.png", noiseImage(32, 32));
  std::ifstream in(png, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string cut = (dir() / "cut.png").string();
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  expectError(cut, "not a readable PNG or JPEG image");
  const std::string text = (dir() / "text.png").string();
  std::ofstream(text) << "not an image at all\n";
  expectError(text, "not a readable PNG or JPEG image");
  const std::string empty = (dir() / "empty.jpg").string();
  std::ofstream{empty};
  expectError(empty, "empty");
  expectError((dir() / "missing.png").string(), "cannot open");
  const std::string narrow = writeBgr("narrow.png", noiseImage(1, 8));
  expectError(narrow, "narrower than 2 pixels");
}

}  // namespace
}  // namespace nao
