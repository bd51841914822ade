// The vision on real NAO images (HULKs dataset, CC BY 4.0; ../shared/data/real-nao-images/)
// with the very same parameters as in simulation. Each masked image must have >= 90 % of
// the detected line spots on the mask's line pixels, and every ball the mask shows at least
// 15 px across must be found, and no ball be seen off the mask's balls.
//
// The photos come without the robot's joint angles. The camera is taken to be a standing
// NAO's top camera, pitched so that the masked ball (the largest one, if any) has its true
// size at its place: what the robot would know from its head joints. Without a ball, the
// pitch at which the mask's lines have the width of field lines (pitchFromLines); without a
// mask 20 deg (the horizon above the image, as in these photos).
//
// NAO_VISION_DOCS=DIR writes the annotated images (docs/vision/real/ holds them).
// NAO_BALLDEBUG=1 (2: with the outline points) and NAO_PITCHPROBE=1 print debugging aids.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "controllers/StandController.h"
#include "perception/CameraModel.h"
#include "perception/vision/Annotate.h"
#include "perception/vision/BallDetector.h"
#include "perception/vision/LineDetector.h"
#include "perception/vision/ScanLineRegionizer.h"
#include "perception/vision/VisionPipeline.h"
#include "robot/Error.h"
#include "sim/ImageIO.h"

namespace nao {
namespace {

namespace fs = std::filesystem;

const std::string kDir = std::string(NAO_SHARED_DIR) + "/data/real-nao-images";

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

struct MaskBall {
  Eigen::Vector2d centre;
  double radius;  // px, from the component's width (it may be cut by the image border)
  double across;  // px
};

struct Mask {
  cv::Mat line;  // CV_8U, 255 on line pixels
  cv::Mat ball;  // CV_8U, 255 on ball pixels (balls of any size)
  std::vector<MaskBall> balls;
};

Mask loadMask(const std::string& path) {
  const cv::Mat m = cv::imread(path, cv::IMREAD_COLOR);
  if (m.empty()) throw Error(path, "cannot read the mask");
  Mask out;
  out.line = cv::Mat::zeros(m.rows, m.cols, CV_8U);
  out.ball = cv::Mat::zeros(m.rows, m.cols, CV_8U);
  cv::Mat& ball = out.ball;
  for (int y = 0; y < m.rows; ++y)
    for (int x = 0; x < m.cols; ++x) {
      const MaskClass c = classOf(m.at<cv::Vec3b>(y, x));
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

CameraMatrix standingCamera(double headPitchDeg, int width, int height) {
  JointArray joints = StandController::standPosture();
  joints[HeadPitch] = headPitchDeg * M_PI / 180;
  return computeCameraMatrix(joints, Eigen::Vector2d::Zero(), CameraId::Top, CameraCalibration{},
                             CameraIntrinsics::fromFovY(width, height));
}

// The head pitch at which a 10 cm ball at `centre` looks `radius` px large.
double pitchFromBall(const MaskBall& b, int width, int height) {
  double best = 20, bestErr = 1e9;
  for (double p = -15; p <= 45; p += 0.25) {
    const double r = vision::expectedBallRadius(standingCamera(p, width, height), b.centre, 0.05);
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
    const CameraMatrix cm = standingCamera(p, width, height);
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

// A ball percept on the mask's ball pixels (a ball of any size): within its radius (at
// least 3 px) of its centre.
bool onMaskBall(const BallPercept& b, const cv::Mat& ballMask) {
  const double reach = std::max(3.0, b.radiusPx);
  for (int y = static_cast<int>(b.image.y() - reach); y <= static_cast<int>(b.image.y() + reach); ++y)
    for (int x = static_cast<int>(b.image.x() - reach); x <= static_cast<int>(b.image.x() + reach); ++x)
      if (x >= 0 && y >= 0 && x < ballMask.cols && y < ballMask.rows && ballMask.at<std::uint8_t>(y, x) &&
          (Eigen::Vector2d(x + 0.5, y + 0.5) - b.image).norm() <= reach)
        return true;
  return false;
}

// Fraction of spots within `tolerancePx` of a mask line pixel.
double spotsOnLines(const std::vector<LinesPercept::Line>& lines, const cv::Mat& lineMask, int tolerancePx,
                    int& total) {
  total = 0;
  int on = 0;
  for (const auto& l : lines)
    for (const auto& s : l.spots) {
      ++total;
      const int x = static_cast<int>(s.x()), y = static_cast<int>(s.y());
      bool hit = false;
      for (int dy = -tolerancePx; dy <= tolerancePx && !hit; ++dy)
        for (int dx = -tolerancePx; dx <= tolerancePx && !hit; ++dx) {
          const int xx = x + dx, yy = y + dy;
          hit = xx >= 0 && yy >= 0 && xx < lineMask.cols && yy < lineMask.rows && lineMask.at<std::uint8_t>(yy, xx);
        }
      on += hit;
    }
  return total ? static_cast<double>(on) / total : 1.0;
}

// Debugging aid (NAO_BALLDEBUG=1): the field reference and every ball candidate near a
// masked ball (or accepted anywhere), with the verifier's measurements and its verdict.
void printBallCandidates(const CameraImage& img, const CameraMatrix& cm, const Mask& mask) {
  const FieldSegmentation seg = segmentField(img, cm);
  const vision::FieldReference field = vision::FieldReference::from(seg.regions);
  std::printf("  field: hue %.2f..%.2f satMin %.1f y %.0f..%.0f fieldY %.0f white (%.3f, %.3f) relSatPerY %.3f\n",
              field.hueMin, field.hueMax, field.satMin, field.yMin, field.yMax, field.fieldY, field.whiteU,
              field.whiteV, field.fieldRelSatPerY);
  std::vector<vision::BallCandidate> cands;
  vision::detectBall(img, seg.regions, field, seg.obstacles, cm, vision::BallParams{}, &cands);
  for (const auto& c : cands) {
    bool near = c.accepted;
    for (const MaskBall& b : mask.balls) near = near || (c.seed - b.centre).norm() < 2.5 * b.radius;
    if (!near) continue;
    std::printf("  cand seed (%.0f,%.0f) r %.1f prio %d %s%s -> %s; circle (%.1f,%.1f) r %.1f inl %d off %d contrast %.2f "
                "dark %.2f pattern %.3f fieldIn %.2f around %.2f sat %.1f/%.1f support %.2f bright %.0f%s\n",
                c.seed.x(), c.seed.y(), c.expectedRadius, c.priority, c.alongVertical ? "V" : "H",
                c.fromPatch ? " patch" : "", c.accepted ? "ACCEPTED" : c.rejectedBy, c.centre.x(), c.centre.y(),
                c.radius, c.inliers, c.offImage, c.contrast, c.darkRatio, c.pattern, c.fieldInside, c.fieldAround,
                c.satInside, c.satAround, c.support, c.bright, c.byBrightOutline ? " (bright outline)" : "");
    if (const char* level = std::getenv("NAO_BALLDEBUG"); level && level[0] == '2') {
      std::printf("    outline:");
      for (const auto& p : c.outline) std::printf(" (%.0f,%.0f)", p.x(), p.y());
      std::printf("\n");
    }
  }
}

TEST(RealImages, LineSpotsOnLinesAndEveryBallFound) {
  const auto images = realImages();
  if (images.empty()) GTEST_SKIP() << kDir << " is missing";
  const char* docs = std::getenv("NAO_VISION_DOCS");
  int masked = 0;
  for (const RealImage& ri : images) {
    SCOPED_TRACE(ri.stem);
    const CameraImage img = sim::readImage(kDir + "/" + ri.stem + "_RGB.png");
    Mask mask;
    if (ri.masked) mask = loadMask(kDir + "/" + ri.stem + ".png");
    double pitch = 20;
    if (!mask.balls.empty()) {
      const auto largest = std::max_element(mask.balls.begin(), mask.balls.end(),
                                            [](const MaskBall& a, const MaskBall& b) { return a.radius < b.radius; });
      pitch = pitchFromBall(*largest, img.width, img.height);
    } else if (ri.masked) {
      pitch = pitchFromLines(mask.line, img.width, img.height, 0.05);
    }
    const CameraMatrix cm = standingCamera(pitch, img.width, img.height);
    const VisionResult r = runVision(img, cm);
    if (docs) sim::writePng(std::string(docs) + "/" + ri.stem + ".png", annotateVision(sim::rgbFromCameraImage(img), r, cm));
    if (!ri.masked) {
      std::printf("%s (no mask): ball %s at (%.0f, %.0f)\n", ri.stem.c_str(), r.ball.seen ? "seen" : "not seen",
                  r.ball.image.x(), r.ball.image.y());
      continue;
    }
    ++masked;
    int spots = 0;
    const double onLines = spotsOnLines(r.lines.lines, mask.line, 2, spots);
    std::printf("%s: head pitch %.1f deg, %zu lines, %d spots, %.1f %% on mask lines; %zu balls >= 15 px, ball %s\n",
                ri.stem.c_str(), pitch, r.lines.lines.size(), spots, 100 * onLines, mask.balls.size(),
                r.ball.seen ? "seen" : "not seen");
    EXPECT_GE(onLines, 0.9) << spots << " spots";
    if (std::getenv("NAO_BALLDEBUG")) printBallCandidates(img, cm, mask);
    // Debugging aid (NAO_PITCHPROBE=1): the same image at head pitches up to 3 deg off the
    // estimate -- is the ball found, missed, or a false ball seen instead?
    if (std::getenv("NAO_PITCHPROBE") && !mask.balls.empty()) {
      const MaskBall& b = mask.balls.front();
      for (double d = -3; d <= 3; d += 0.5) {
        const CameraMatrix cm2 = standingCamera(pitch + d, img.width, img.height);
        const VisionResult r2 = runVision(img, cm2);
        const char* verdict = !r2.ball.seen                                              ? "none"
                              : (r2.ball.image - b.centre).norm() < std::max(b.radius, 6.0) ? "found"
                              : onMaskBall(r2.ball, mask.ball)                            ? "another mask ball"
                                                                                          : "FALSE";
        std::printf("  pitch %+.1f deg: %s (%.0f, %.0f)\n", d, verdict, r2.ball.image.x(), r2.ball.image.y());
        if (r2.ball.seen && !onMaskBall(r2.ball, mask.ball)) printBallCandidates(img, cm2, mask);
      }
    }
    // No false ball: a ball percept lies on one of the mask's balls.
    EXPECT_TRUE(!r.ball.seen || onMaskBall(r.ball, mask.ball))
        << "false ball at " << r.ball.image.transpose() << " (r " << r.ball.radiusPx << " px)";
    for (const MaskBall& b : mask.balls) {
      EXPECT_TRUE(r.ball.seen && (r.ball.image - b.centre).norm() < std::max(b.radius, 6.0))
          << "mask ball at " << b.centre.transpose() << " (" << b.across << " px) not found; percept "
          << (r.ball.seen ? "at " : "none ") << r.ball.image.transpose();
    }
  }
  EXPECT_GE(masked, 1);
}

}  // namespace
}  // namespace nao
