// Camera rendering (sim/CameraRenderer), lighting (sim/Lighting), image I/O (sim/ImageIO) and
// the field view (sim/FieldView).
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <numeric>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <string>
#include <vector>

#include "perception/FieldDimensions.h"
#include "robot/Error.h"
#include "robot/Paths.h"
#include "sim/CameraRenderer.h"
#include "sim/FieldView.h"
#include "sim/ImageIO.h"
#include "sim/Lighting.h"
#include "sim/SceneBuilder.h"
#include "tests/support/DownCamera.h"

namespace {

using namespace nao;
using namespace nao::sim;
namespace fs = std::filesystem;

const char* const kDownCamera = test::kDownCameraMjcf;

class TempDir {
 public:
  TempDir() : path_(fs::temp_directory_path() / ("nao_render_test_" + std::to_string(::getpid()))) {
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string path(const std::string& name) const { return (path_ / name).string(); }
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(path(name), std::ios::binary) << bytes;
    return path(name);
  }

 private:
  fs::path path_;
};

std::string presets() { return dataPath("config/lighting.json"); }

// The down-looking camera over (x, y), field from config/field_dimensions.json.
class DownCamera {
 public:
  explicit DownCamera(const TempDir& dir, double x = 0.2, double y = 0.3) {
    SceneSpec spec;
    spec.field = FieldDimensions::load(dataPath("config/field_dimensions.json"));
    spec.robotModel = dir.write("down_camera.xml", kDownCamera);
    spec.robots = {Eigen::Vector3d(x, y, 0)};
    m = compileScene(spec);
    d = mj_makeData(m);
    mj_forward(m, d);
    camera = mj_name2id(m, mjOBJ_CAMERA, "r0/CameraTop");
  }
  ~DownCamera() {
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  DownCamera(const DownCamera&) = delete;
  DownCamera& operator=(const DownCamera&) = delete;
  mjModel* m;
  mjData* d;
  int camera;
};

double meanY(const CameraImage& image) {
  double sum = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) sum += image.y(x, y);
  return sum / (image.width * image.height);
}

TEST(RenderTest, PaintLandsExactlyWhereThePinholeModelPutsIt) {
  TempDir dir;
  const double cx = 0.2, cy = 0.3;  // camera over (cx, cy), 1 m above the carpet
  DownCamera scene(dir, cx, cy);
  CameraRenderer renderer(scene.m);
  Lighting lighting;
  const int w = 640, h = 480;
  const cv::Mat rgb = renderer.renderRgb(scene.m, scene.d, scene.camera, w, h, lighting);
  ASSERT_EQ(rgb.type(), CV_8UC3);
  ASSERT_EQ(rgb.cols, w);
  ASSERT_EQ(rgb.rows, h);

  const double f = (h / 2.0) / std::tan(43.7 / 2 * std::numbers::pi / 180);
  const double height = 1.0 - 0.0005;      // down to the paint's top
  const double margin = 1.0 * height / f;  // one pixel on the carpet
  int checked = 0, wrong = 0, white = 0;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      // The pixel centre's ray hits the carpet at (x, y): image up = +x, image right = -y.
      const double x = cx - (j + 0.5 - h / 2.0) * height / f;
      const double y = cy - (i + 0.5 - w / 2.0) * height / f;
      // Signed distances (inside < 0) to the paint: halfway line, centre dash, centre circle.
      const double line = std::abs(x) - 0.025;
      const double dash = std::max(std::abs(x) - 0.05, std::abs(y) - 0.025);
      const double circle = std::abs(std::hypot(x, y) - 0.75) - 0.025;
      if (std::abs(line) < margin || std::abs(dash) < margin || std::abs(circle) < margin) continue;
      const bool paint = line < 0 || dash < 0 || circle < 0;
      const cv::Vec3b p = rgb.at<cv::Vec3b>(j, i);
      const bool looksWhite = p[0] > 150 && p[1] > 150 && p[2] > 150;
      const bool looksGreen = p[1] > p[0] + 30 && p[1] > p[2] + 30;
      ++checked;
      white += paint;
      if (paint ? !looksWhite : !looksGreen) ++wrong;
    }
  }
  EXPECT_GT(white, 10000);  // the halfway line, the dash and a piece of the circle are in view
  EXPECT_GT(checked, w * h * 9 / 10);
  EXPECT_EQ(wrong, 0) << "of " << checked << " pixels";
  // Orientation: the centre dash is to the image's right (-y) and below the centre (-x).
  const cv::Vec3b dash = rgb.at<cv::Vec3b>(360, 500);
  EXPECT_GT(std::min({dash[0], dash[1], dash[2]}), 150);

  // Sub-pixel: paint coverage (from the red channel, carpet ~55, paint ~230) gives each
  // stripe's centroid and width; they match the pinhole model to a fraction of a pixel
  // (a half-pixel convention error would show).
  const double carpet = cv::mean(rgb(cv::Rect(200, 60, 240, 80)))[0];
  const double paint = cv::mean(rgb(cv::Rect(250, 352, 200, 16)))[0];
  auto coverage = [&](int j, int i) { return (rgb.at<cv::Vec3b>(j, i)[0] - carpet) / (paint - carpet); };
  for (int i = 250; i <= 450; i += 50) {  // the halfway line across columns clear of the dash
    double sum = 0, moment = 0;
    for (int j = 300; j < 420; ++j) sum += coverage(j, i), moment += coverage(j, i) * (j + 0.5);
    EXPECT_NEAR(moment / sum, h / 2.0 + f * cx / height, 0.2) << "column " << i;
    EXPECT_NEAR(sum, f * 0.05 / height, 0.4) << "column " << i;
  }
  for (int j = 332; j <= 342; j += 5) {  // the dash where it sticks out of the halfway line
    double sum = 0, moment = 0;
    for (int i = 440; i < 560; ++i) sum += coverage(j, i), moment += coverage(j, i) * (i + 0.5);
    EXPECT_NEAR(moment / sum, w / 2.0 + f * cy / height, 0.2) << "row " << j;
    EXPECT_NEAR(sum, f * 0.05 / height, 0.4) << "row " << j;
  }
}

TEST(RenderTest, SameSeedSameBytesOtherSeedOnlyNoise) {
  TempDir dir;
  DownCamera scene(dir);
  CameraRenderer renderer(scene.m);
  Lighting lighting;
  lighting.noise = 2.0;
  // Each image from a settled camera (the exposure loop would otherwise move between them).
  auto shoot = [&](std::mt19937_64& rng, CameraId id) {
    renderer.resetCameraSensors();
    return renderer.renderImage(scene.m, scene.d, scene.camera, 320, 240, lighting, id, 1.5, rng, ExposureWeights{});
  };
  std::mt19937_64 a(7), b(7), c(8);
  const CameraImage ia = shoot(a, CameraId::Bottom), ib = shoot(b, CameraId::Bottom), ic = shoot(c, CameraId::Bottom);
  ASSERT_TRUE(ia.valid());
  EXPECT_EQ(ia.camera, CameraId::Bottom);
  EXPECT_EQ(ia.timestamp, 1.5);
  EXPECT_EQ(ia.yuyv, ib.yuyv);
  ASSERT_EQ(ia.yuyv.size(), ic.yuyv.size());
  std::size_t differing = 0;
  int maxDiff = 0;
  double meanDiff = 0;
  for (std::size_t k = 0; k < ia.yuyv.size(); ++k) {
    const int diff = int(ia.yuyv[k]) - int(ic.yuyv[k]);
    differing += diff != 0;
    maxDiff = std::max(maxDiff, std::abs(diff));
    meanDiff += diff;
  }
  meanDiff /= ia.yuyv.size();
  EXPECT_GT(differing, ia.yuyv.size() / 2);
  EXPECT_LE(maxDiff, 40);  // two draws of read and shot noise (about 3 Y units), each within 6 sigma
  EXPECT_LT(std::abs(meanDiff), 0.05);
  // Without noise the seed does not matter.
  lighting.noise = 0;
  EXPECT_EQ(shoot(a, CameraId::Top).yuyv, shoot(c, CameraId::Top).yuyv);
}

// The flat noise (the camera model switched off): zero mean, sigma on Y and sigma/2 on U and V,
// clamped into bytes at both ends, the same bytes for the same seed.
TEST(RenderTest, SensorNoiseHasItsSigmaAndIsClampedIntoBytes) {
  for (double sigma : {0.7, 2.0, 40.0}) {
    CameraImage image;
    image.width = 256;
    image.height = 64;
    image.yuyv.resize(static_cast<std::size_t>(image.width) * image.height * 2);
    for (std::size_t k = 0; k < image.yuyv.size(); ++k) image.yuyv[k] = static_cast<std::uint8_t>(k % 256);
    const std::vector<std::uint8_t> before = image.yuyv;
    CameraImage again = image;
    std::mt19937_64 rng(11), same(11);
    addSensorNoise(image, sigma, rng);
    addSensorNoise(again, sigma, same);
    EXPECT_EQ(image.yuyv, again.yuyv);
    double sum[2] = {0, 0}, sum2[2] = {0, 0};
    int n[2] = {0, 0}, clamped = 0;
    for (std::size_t k = 0; k < before.size(); ++k) {
      clamped += image.yuyv[k] == 0 || image.yuyv[k] == 255;
      if (before[k] < 40 || before[k] > 215) continue;  // away from the clamps
      const int channel = k % 2 == 0 ? 0 : 1;            // Y, or U and V
      const double diff = double(image.yuyv[k]) - before[k];
      sum[channel] += diff;
      sum2[channel] += diff * diff;
      ++n[channel];
    }
    for (int channel : {0, 1}) {
      const double expected = channel == 0 ? sigma : sigma / 2;
      const double mean = sum[channel] / n[channel], sd = std::sqrt(sum2[channel] / n[channel] - mean * mean);
      EXPECT_NEAR(mean, 0, 0.05 * expected + 0.02) << sigma;
      EXPECT_NEAR(sd, std::sqrt(expected * expected + 1.0 / 12), 0.06 * expected + 0.05) << sigma;  // + rounding
    }
    if (sigma > 10) {
      EXPECT_GT(clamped, 100);
    }
  }
}

TEST(RenderTest, TwoRenderersTakeTurns) {
  TempDir dir;
  DownCamera scene(dir);
  Lighting lighting;
  CameraRenderer first(scene.m);
  const cv::Mat alone = first.renderRgb(scene.m, scene.d, scene.camera, 320, 240, lighting);
  CameraRenderer second(scene.m);
  const cv::Mat fromSecond = second.renderRgb(scene.m, scene.d, scene.camera, 320, 240, lighting);
  const cv::Mat fromFirst = first.renderRgb(scene.m, scene.d, scene.camera, 320, 240, lighting);
  EXPECT_EQ(cv::norm(alone, fromFirst, cv::NORM_INF), 0);
  EXPECT_EQ(cv::norm(alone, fromSecond, cv::NORM_INF), 0);
  EXPECT_THROW(first.renderRgb(scene.m, scene.d, scene.camera, 1280, 960, lighting), Error);
  EXPECT_THROW(first.renderRgb(scene.m, scene.d, 99, 320, 240, lighting), Error);
}

TEST(RenderTest, DarkIsDarkerThanBrightUnlessTheExposureSettles) {
  TempDir dir;
  DownCamera scene(dir);
  CameraRenderer renderer(scene.m);
  std::mt19937_64 rng(1);
  auto mean = [&](const std::string& preset) {
    renderer.resetCameraSensors();
    return meanY(renderer.renderImage(scene.m, scene.d, scene.camera, 320, 240, Lighting::parse(preset, presets()),
                                      CameraId::Top, 0, rng, ExposureWeights{}));
  };
  // The scene itself (no auto exposure):
  const double dark = mean("dark,ae=off"), normal = mean("default,ae=off"), bright = mean("bright,ae=off");
  EXPECT_LT(dark, normal);
  EXPECT_LT(normal, bright);
  EXPECT_LT(dark, 0.5 * bright);
  // A camera that has settled in each light brings all three near its target.
  const double target = CameraSensorParams::load(dataPath("config/camera_sensor.json")).targetLuma;
  for (const char* preset : {"dark", "default", "bright"}) EXPECT_NEAR(mean(preset), target, 8) << preset;
  EXPECT_GT(renderer.cameraExposure(scene.camera).exposureMs, 0);
  // Shadows render (the camera sees its own shadow-free field; only that it works is checked).
  EXPECT_GT(mean("shadows"), 10);
}

TEST(LightingTest, PresetsAndLists) {
  const Lighting def = Lighting::parse("default", presets());
  const Lighting builtin;
  EXPECT_EQ(def.name, "default");
  EXPECT_DOUBLE_EQ(def.intensity, builtin.intensity);
  EXPECT_DOUBLE_EQ(def.temperature, builtin.temperature);
  EXPECT_EQ(def.shadows, builtin.shadows);
  EXPECT_DOUBLE_EQ(def.elevation, builtin.elevation);
  EXPECT_DOUBLE_EQ(def.azimuth, builtin.azimuth);
  EXPECT_DOUBLE_EQ(def.ambient, builtin.ambient);
  EXPECT_DOUBLE_EQ(def.noise, builtin.noise);
  for (const char* name : {"bright", "dark", "warm", "cold", "shadows"})
    EXPECT_EQ(Lighting::parse(name, presets()).name, name);
  EXPECT_TRUE(Lighting::parse("shadows", presets()).shadows);

  const Lighting l = Lighting::parse(
      "intensity=0.4,temperature=3200,shadows=on,elevation=35,azimuth=120,ambient=0.2,noise=2", presets());
  EXPECT_DOUBLE_EQ(l.intensity, 0.4);
  EXPECT_DOUBLE_EQ(l.temperature, 3200);
  EXPECT_TRUE(l.shadows);
  EXPECT_DOUBLE_EQ(l.elevation, 35);
  EXPECT_DOUBLE_EQ(l.ambient, 0.2);
  EXPECT_DOUBLE_EQ(l.noise, 2);
  // A preset with overrides.
  const Lighting d = Lighting::parse("dark, shadows=on", presets());
  EXPECT_TRUE(d.shadows);
  EXPECT_DOUBLE_EQ(d.intensity, Lighting::parse("dark", presets()).intensity);

  const std::vector<Lighting> sweep = Lighting::sweep(presets());
  ASSERT_GE(sweep.size(), 5u);
  double lo = 1e9, hi = 0, tlo = 1e9, thi = 0;
  bool anyShadows = false;
  for (const Lighting& s : sweep) {
    lo = std::min(lo, s.intensity), hi = std::max(hi, s.intensity);
    tlo = std::min(tlo, s.temperature), thi = std::max(thi, s.temperature);
    anyShadows = anyShadows || s.shadows;
  }
  EXPECT_LE(lo, 0.25);
  EXPECT_GE(hi, 2.5);
  EXPECT_LE(tlo, 2700);
  EXPECT_GE(thi, 6500);
  EXPECT_TRUE(anyShadows);
}

TEST(LightingTest, ColourTemperature) {
  Lighting l;
  l.temperature = 2700;
  const Eigen::Vector3d warm = l.colour();
  l.temperature = 6500;
  const Eigen::Vector3d cold = l.colour();
  EXPECT_DOUBLE_EQ(warm.maxCoeff(), 1.0);
  EXPECT_DOUBLE_EQ(cold.maxCoeff(), 1.0);
  EXPECT_DOUBLE_EQ(warm.x(), 1.0);
  EXPECT_LT(warm.z(), 0.45);
  EXPECT_GT(cold.z(), 0.95);
  EXPECT_GT(cold.y(), 0.95);
  EXPECT_GT(warm.x() / warm.z(), cold.x() / cold.z());
}

TEST(LightingTest, ErrorsNameTheFlagOrFileAndTheKey) {
  auto expectError = [](const std::string& spec, const std::string& file, const std::string& where,
                        const std::string& part) {
    try {
      Lighting::parse(spec, file);
      ADD_FAILURE() << "no error for '" << spec << "'";
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), where) << e.what();
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  expectError("x=1", presets(), "--lighting", "unknown key 'x'");
  expectError("intensity=-1", presets(), "--lighting", "intensity");
  expectError("intensity=abc", presets(), "--lighting", "not a number");
  expectError("temperature=100", presets(), "--lighting", "temperature");
  expectError("noise=nan", presets(), "--lighting", "noise");
  expectError("shadows=maybe", presets(), "--lighting", "shadows");
  expectError("intensity=1,,noise=2", presets(), "--lighting", "empty");
  expectError("intensity", presets(), "--lighting", "unknown preset 'intensity'");
  expectError("disco", presets(), "--lighting", "unknown preset 'disco'");
  expectError("", presets(), "--lighting", "empty");
  expectError("sweep", presets(), "--lighting", "sweep");

  TempDir dir;
  const std::string bad = dir.write("lighting.json", R"({"presets": {"odd": "intensity=1,glow=3"}, "sweep": ["odd"]})");
  expectError("odd", bad, bad, "presets.odd: unknown key 'glow'");
  EXPECT_THROW(Lighting::sweep(bad), Error);
  const std::string broken = dir.write("broken.json", "{\"presets\": ");
  expectError("default", broken, broken, "JSON");
  expectError("default", dir.path("missing.json"), dir.path("missing.json"), "not found");
  // Key lists need no presets file.
  EXPECT_NO_THROW(Lighting::parse("intensity=2", dir.path("missing.json")));
}

TEST(ImageIOTest, YuyvRoundTrip) {
  cv::Mat rgb(48, 64, CV_8UC3);
  for (int r = 0; r < rgb.rows; ++r)
    for (int c = 0; c < rgb.cols; ++c)  // colour constant over each pixel pair
      rgb.at<cv::Vec3b>(r, c) = cv::Vec3b(static_cast<uchar>(4 * r + 20), static_cast<uchar>(3 * (c / 2) + 30),
                                          static_cast<uchar>(200 - 2 * r));
  const cv::Mat yuyv = yuyvFromRgb(rgb);
  ASSERT_EQ(yuyv.type(), CV_8UC2);
  const cv::Mat back = rgbFromYuyv(yuyv);
  EXPECT_LE(cv::norm(rgb, back, cv::NORM_INF), 2);

  // Known values (BT.601 full range): white, green.
  cv::Mat two(1, 4, CV_8UC3);
  two.at<cv::Vec3b>(0, 0) = two.at<cv::Vec3b>(0, 1) = cv::Vec3b(255, 255, 255);
  two.at<cv::Vec3b>(0, 2) = two.at<cv::Vec3b>(0, 3) = cv::Vec3b(0, 255, 0);
  const CameraImage image = cameraImageFromRgb(two);
  EXPECT_EQ(image.y(0, 0), 255);
  EXPECT_EQ(image.u(1, 0), 128);
  EXPECT_EQ(image.v(1, 0), 128);
  EXPECT_EQ(image.y(2, 0), 150);
  EXPECT_EQ(image.u(3, 0), 44);
  EXPECT_EQ(image.v(3, 0), 21);
  // U/V average over the pair.
  two.at<cv::Vec3b>(0, 1) = cv::Vec3b(0, 0, 255);
  const CameraImage mixed = cameraImageFromRgb(two);
  EXPECT_EQ(mixed.u(0, 0), 192);  // (128 + 255.5) / 2, rounded

  // PNG and raw files.
  TempDir dir;
  const CameraImage original = cameraImageFromRgb(rgb, CameraId::Top, 0);
  writePng(dir.path("a.png"), original);
  const CameraImage png = readImage(dir.path("a.png"));
  ASSERT_TRUE(png.valid());
  ASSERT_EQ(png.width, 64);
  ASSERT_EQ(png.height, 48);
  for (std::size_t k = 0; k < png.yuyv.size(); ++k)
    ASSERT_LE(std::abs(int(png.yuyv[k]) - int(original.yuyv[k])), 2) << k;
  const std::string raw = dir.write("a.yuyv", std::string(original.yuyv.begin(), original.yuyv.end()));
  const CameraImage fromRaw = readImage(raw, 64, 48, CameraId::Bottom);
  EXPECT_EQ(fromRaw.yuyv, original.yuyv);
  EXPECT_EQ(fromRaw.camera, CameraId::Bottom);
}

TEST(ImageIOTest, BadFilesGiveErrorsNotCrashes) {
  TempDir dir;
  cv::Mat rgb(48, 64, CV_8UC3, cv::Scalar(10, 200, 30));
  writePng(dir.path("good.png"), rgb);
  std::ifstream in(dir.path("good.png"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto expectError = [&](const std::string& path, int w, int h) {
    try {
      readImage(path, w, h);
      ADD_FAILURE() << "no error for " << path;
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), path);
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  };
  expectError(dir.write("truncated.png", bytes.substr(0, bytes.size() / 3)), 0, 0);
  std::vector<uchar> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", rgb, jpeg));
  const std::string jpegBytes(jpeg.begin(), jpeg.end());
  EXPECT_EQ(readImage(dir.write("good.jpg", jpegBytes)).width, 64);
  expectError(dir.write("truncated.jpg", jpegBytes.substr(0, jpegBytes.size() / 2)), 0, 0);
  expectError(dir.write("garbage.png", std::string(500, 'x')), 0, 0);
  expectError(dir.write("empty.jpg", ""), 0, 0);
  expectError(dir.path("missing.png"), 0, 0);
  expectError(dir.write("short.yuyv", std::string(1000, '\0')), 64, 48);
  expectError(dir.write("unsized.yuv", std::string(1000, '\0')), 0, 0);
  expectError(dir.write("odd.yuv", std::string(63 * 48 * 2, '\0')), 63, 48);
  // Standard sizes are recognised without --size.
  EXPECT_EQ(readImage(dir.write("qvga.yuv", std::string(320 * 240 * 2, '\x80'))).width, 320);
  // A file that cannot be written is a failed run (exit 1), not bad input.
  EXPECT_THROW(writePng(dir.path("no_such_dir/x.png"), rgb), nao::RunFailure);
  EXPECT_THROW(writePng(dir.path("bad.png"), CameraImage{}), Error);
}

TEST(FieldViewTest, DrawsTheFieldTopDown) {
  const FieldModel field = FieldModel::from(FieldDimensions::load(dataPath("config/field_dimensions.json")));
  const int ppm = 50;
  const cv::Mat view = drawFieldView(field, {Eigen::Vector3d(-2, 1, 0)}, {Eigen::Vector3d(1, -1, 0.05)}, ppm);
  ASSERT_EQ(view.type(), CV_8UC3);
  EXPECT_EQ(view.cols, 10.4 * ppm);
  EXPECT_EQ(view.rows, 7.4 * ppm);
  auto at = [&](double x, double y) {
    return view.at<cv::Vec3b>(static_cast<int>((3.7 - y) * ppm), static_cast<int>((x + 5.2) * ppm));
  };
  EXPECT_GT(at(0, 2).val[0], 200);      // halfway line: white
  EXPECT_GT(at(0.75, 0).val[0], 200);   // centre circle
  EXPECT_GT(at(-4.5, -2).val[0], 200);  // own goal line
  const cv::Vec3b carpet = at(2, 1);
  EXPECT_GT(carpet[1], carpet[0] + 50);  // green (RGB order)
  const cv::Vec3b ball = at(1, -1);
  EXPECT_GT(ball[0], ball[2] + 100);  // orange
  const cv::Vec3b robot = at(-2 - 0.1, 1);
  EXPECT_GT(robot[2], robot[1] + 50);  // blue
  EXPECT_THROW(drawFieldView(field, {}, {}, 0), Error);
}

}  // namespace

namespace {

TEST(ImageIOTest, ReadsRealNaoImages) {
  const std::string path = std::string(NAO_SHARED_DIR) + "/data/real-nao-images/00096_RGB.png";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not present";
  const nao::CameraImage image = nao::sim::readImage(path);
  ASSERT_TRUE(image.valid());
  EXPECT_EQ(image.width, 640);
  EXPECT_EQ(image.height, 480);
}

}  // namespace
