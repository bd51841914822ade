#include "RealImages.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "controllers/StandController.h"
#include "perception/vision/Annotate.h"
#include "perception/vision/BallDetector.h"
#include "perception/vision/LineDetector.h"
#include "robot/Error.h"
#include "sim/ImageIO.h"

namespace nao::test {
namespace {

namespace fs = std::filesystem;

const std::string kDir = realImagesDir();

// The masks' palette (RGB).
enum class MaskClass { Field, Line, Ball, Goal, Robot, Other, Uncertain };
MaskClass classOf(const cv::Vec3b& bgr) {
  struct Entry {
    int r, g, b;
    MaskClass c;
  };
  static const Entry palette[] = {{245, 41, 5, MaskClass::Field},   {70, 199, 10, MaskClass::Line},
                                  {199, 92, 10, MaskClass::Ball},   {199, 10, 193, MaskClass::Goal},
                                  {10, 193, 199, MaskClass::Robot}, {45, 10, 199, MaskClass::Other},
                                  {0, 0, 0, MaskClass::Uncertain}};
  int best = 1 << 30;
  MaskClass c = MaskClass::Uncertain;
  for (const auto& e : palette) {
    const int d = std::abs(e.r - bgr[2]) + std::abs(e.g - bgr[1]) + std::abs(e.b - bgr[0]);
    if (d < best) best = d, c = e.c;
  }
  return c;
}

// The head pitch at which a 10 cm ball at `centre` looks `radius` px large.
double pitchFromBall(const MaskBall& b, int width, int height) {
  double best = 20, bestErr = 1e9;
  for (double p = -15; p <= 45; p += 0.25) {
    const double r = vision::expectedBallRadius(photoCamera(p, width, height), b.centre, 0.05);
    if (r > 0 && std::abs(r - b.radius) < bestErr) bestErr = std::abs(r - b.radius), best = p;
  }
  return best;
}

// Without a ball: the head pitch at which the mask's field lines are as thick as 50 mm lines.
// Along each column the mask's line runs are at least as tall as a line's width along the view
// direction there (exactly that where a line runs across the view, taller where it is seen
// obliquely), so the pitch is the one that brings the low end of the ratios (the 15th
// percentile) to 1. Runs cut by the image border do not count.
double pitchFromLines(const cv::Mat& lineMask, int width, int height, double lineWidth) {
  struct Run {
    double x, y, len;
  };
  std::vector<Run> runs;
  for (int x = 2; x < lineMask.cols; x += 6) {
    int y = 0;
    while (y < lineMask.rows) {
      if (!lineMask.at<std::uint8_t>(y, x)) {
        ++y;
        continue;
      }
      const int y0 = y;
      while (y < lineMask.rows && lineMask.at<std::uint8_t>(y, x)) ++y;
      if (y0 > 0 && y < lineMask.rows && y - y0 >= 2) runs.push_back({x + 0.5, 0.5 * (y0 + y), double(y - y0)});
    }
  }
  if (runs.size() < 10) return 20;
  double best = 20, bestErr = 1e9;
  std::vector<double> ratios;
  for (double p = -15; p <= 45; p += 0.25) {
    const CameraMatrix cm = photoCamera(p, width, height);
    ratios.clear();
    for (const Run& r : runs) {
      const vision::GroundScale gs = vision::groundScale(cm, {r.x, r.y}, lineWidth);
      if (gs.valid && gs.alongPx > 0.3) ratios.push_back(r.len / gs.alongPx);
    }
    if (ratios.size() < 10) continue;
    std::nth_element(ratios.begin(), ratios.begin() + ratios.size() * 15 / 100, ratios.end());
    const double err = std::abs(std::log(ratios[ratios.size() * 15 / 100]));
    if (err < bestErr) bestErr = err, best = p;
  }
  return best;
}

struct RealImage {
  std::string stem;  // NNNNN
  bool masked = false;
};

std::vector<RealImage> realImages() {
  std::vector<RealImage> out;
  if (!fs::is_directory(kDir)) return out;
  for (const auto& e : fs::directory_iterator(kDir)) {
    const std::string name = e.path().filename().string();
    const auto pos = name.find("_RGB.png");
    if (pos == std::string::npos) continue;
    const std::string stem = name.substr(0, pos);
    out.push_back({stem, fs::exists(kDir + "/" + stem + ".png")});
  }
  std::sort(out.begin(), out.end(), [](const RealImage& a, const RealImage& b) { return a.stem < b.stem; });
  return out;
}

}  // namespace

std::string realImagesDir() { return std::string(NAO_SHARED_DIR) + "/data/real-nao-images"; }

Mask loadMask(const std::string& path) {
  const cv::Mat m = cv::imread(path, cv::IMREAD_COLOR);
  if (m.empty()) throw Error(path, "cannot read the mask");
  Mask out;
  out.field = cv::Mat::zeros(m.rows, m.cols, CV_8U);
  out.line = cv::Mat::zeros(m.rows, m.cols, CV_8U);
  out.ball = cv::Mat::zeros(m.rows, m.cols, CV_8U);
  cv::Mat& ball = out.ball;
  for (int y = 0; y < m.rows; ++y)
    for (int x = 0; x < m.cols; ++x) {
      const MaskClass c = classOf(m.at<cv::Vec3b>(y, x));
      if (c == MaskClass::Field) out.field.at<std::uint8_t>(y, x) = 255;
      if (c == MaskClass::Line) out.line.at<std::uint8_t>(y, x) = 255;
      if (c == MaskClass::Ball) ball.at<std::uint8_t>(y, x) = 255;
    }
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(ball, labels, stats, centroids);
  for (int k = 1; k < n; ++k) {
    const int x = stats.at<int>(k, cv::CC_STAT_LEFT), y = stats.at<int>(k, cv::CC_STAT_TOP);
    const int w = stats.at<int>(k, cv::CC_STAT_WIDTH), h = stats.at<int>(k, cv::CC_STAT_HEIGHT);
    const double across = std::max(w, h);
    if (across < 15) continue;
    // A ball cut by the image's bottom edge keeps its full width.
    const double r = 0.5 * across;
    const double cy = y + h >= m.rows - 1 && w > h ? y + r : y + 0.5 * h;
    out.balls.push_back({Eigen::Vector2d(x + 0.5 * w, cy), r, across});
  }
  return out;
}

CameraMatrix photoCamera(double headPitchDeg, int width, int height) {
  JointArray joints = StandController::standPosture();
  joints[HeadPitch] = headPitchDeg * M_PI / 180;
  return computeCameraMatrix(joints, Eigen::Vector2d::Zero(), CameraId::Top, CameraCalibration{},
                             CameraIntrinsics::fromFovY(width, height));
}

const std::vector<Evaluated>& evaluatedRealImages() {
  static const std::vector<Evaluated> all = [] {
    std::vector<Evaluated> out;
    const char* docs = std::getenv("NAO_VISION_DOCS");
    for (const RealImage& ri : realImages()) {
      Evaluated e;
      e.stem = ri.stem;
      e.masked = ri.masked;
      e.image = sim::readImage(kDir + "/" + ri.stem + "_RGB.png");
      if (ri.masked) e.mask = loadMask(kDir + "/" + ri.stem + ".png");
      if (!e.mask.balls.empty()) {
        const auto largest = std::max_element(e.mask.balls.begin(), e.mask.balls.end(),
                                              [](const MaskBall& a, const MaskBall& b) { return a.radius < b.radius; });
        e.pitch = pitchFromBall(*largest, e.image.width, e.image.height);
      } else if (ri.masked) {
        e.pitch = pitchFromLines(e.mask.line, e.image.width, e.image.height, 0.05);
      }
      e.cm = photoCamera(e.pitch, e.image.width, e.image.height);
      e.result = runVision(e.image, e.cm);
      if (docs)
        sim::writePng(std::string(docs) + "/" + ri.stem + ".png",
                      annotateVision(sim::rgbFromCameraImage(e.image), e.result, e.cm));
      out.push_back(std::move(e));
    }
    return out;
  }();
  return all;
}

}  // namespace nao::test
