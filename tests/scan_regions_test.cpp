// The first half of the vision (scan grid, YHS2, colour-segmented scan lines, field boundary,
// obstacles) on synthetic images drawn pixel by pixel through a camera matrix (so the truth
// of every pixel is known), under different brightness, colour casts, shadows and noise,
// and on the real NAO images with their segmentation masks. No simulator: nao_perception only.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "perception/CameraModel.h"
#include "perception/vision/FieldBoundaryDetector.h"
#include "perception/vision/ObstacleDetector.h"
#include "perception/vision/ScanGrid.h"
#include "perception/vision/ScanLineRegionizer.h"
#include "perception/vision/VisionDebug.h"
#include "perception/vision/Yhs.h"

namespace nao {
namespace {

constexpr double kDeg = M_PI / 180;

// RGB (CV_8UC3, RGB order) -> the NAO's YUYV (BT.601 full range, U/V averaged per pixel pair).
CameraImage toCameraImage(const cv::Mat& rgb, CameraId camera = CameraId::Top) {
  CameraImage img;
  img.camera = camera;
  img.width = rgb.cols & ~1;
  img.height = rgb.rows;
  img.yuyv.resize(static_cast<std::size_t>(img.width) * img.height * 2);
  for (int y = 0; y < img.height; ++y) {
    const std::uint8_t* in = rgb.ptr<std::uint8_t>(y);
    std::uint8_t* o = img.yuyv.data() + static_cast<std::size_t>(y) * img.width * 2;
    for (int x = 0; x < img.width; x += 2, in += 6, o += 4) yuyvPairFromRgb(in, o);
  }
  return img;
}

// A camera `height` m above the robot origin, pitched down by `pitch`, yawed by `yaw`.
CameraMatrix cameraAt(double height, double pitch, double yaw = 0, int w = 640, int h = 480) {
  CameraMatrix cm;
  cm.intrinsics = CameraIntrinsics::fromFovY(w, h);
  cm.pose = Eigen::Isometry3d::Identity();
  cm.pose.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()))
                         .toRotationMatrix();
  cm.pose.translation() = Eigen::Vector3d(0, 0, height);
  return cm;
}

// --- Synthetic scenes -----------------------------------------------------------------------

enum Truth : std::uint8_t { kBackground = 0, kField = 1, kLine = 2, kRobot = 3 };

struct Light {
  std::string name;
  double gain = 1;                      // overall brightness
  Eigen::Vector3d cast{1, 1, 1};        // per RGB channel (no white balance)
  double noise = 2;                     // std. dev. per channel
  bool shadow = false;                  // a hard shadow band across the field
};

std::vector<Light> lights() {
  return {{"normal", 1.0, {1, 1, 1}, 2, false},      {"dark", 0.3, {1, 1, 1}, 3, false},
          {"bright", 1.8, {1, 1, 1}, 2, false},      {"warm", 1.0, {1.0, 0.72, 0.42}, 2, false},
          {"cold", 1.0, {0.72, 0.88, 1.0}, 2, false}, {"shadow", 1.2, {1, 1, 1}, 2, true},
          {"noisy", 0.8, {1, 1, 1}, 7, false}};
}

// Ground lines (robot frame, m): across the view, running away, a far one.
struct GroundLine {
  Eigen::Vector2d from, to;
};
const std::vector<GroundLine> kLines = {
    {{1.2, -3.0}, {1.2, 3.0}}, {{3.0, -3.0}, {3.0, 3.0}}, {{0.2, 0.6}, {4.5, 0.6}}, {{0.2, -1.4}, {4.5, -0.9}}};
constexpr double kLineWidth = 0.05;
constexpr double kCarpetEnd = 4.5, kCarpetHalfWidth = 3.5;  // the carpet ends here; a grey hall beyond

bool onLine(const Eigen::Vector2d& p, double margin = 0) {
  for (const auto& l : kLines) {
    const Eigen::Vector2d d = (l.to - l.from).normalized();
    const Eigen::Vector2d q = p - l.from;
    const double t = q.dot(d), n = std::abs(q.x() * d.y() - q.y() * d.x());
    if (t >= -kLineWidth / 2 && t <= (l.to - l.from).norm() + kLineWidth / 2 && n <= kLineWidth / 2 + margin) return true;
  }
  return false;
}

struct Scene {
  cv::Mat rgb;    // CV_8UC3, RGB
  cv::Mat truth;  // CV_8UC1, Truth per pixel (at the pixel centre)
  CameraMatrix cm;
};

// Renders the scene through cm, pixel by pixel. robot: a grey box 0.15 m wide and 0.5 m tall
// standing at robotAt (robot frame), facing the camera.
Scene render(const CameraMatrix& cm, const Light& light, std::uint64_t seed, bool robot = false,
             const Eigen::Vector2d& robotAt = {1.8, 0.3}) {
  const int W = cm.intrinsics.width, H = cm.intrinsics.height;
  Scene s{cv::Mat(H, W, CV_8UC3), cv::Mat(H, W, CV_8UC1), cm};
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0, light.noise);
  const Eigen::Vector3d field(0.22, 0.55, 0.20), paint(0.93, 0.93, 0.93), hall(0.42, 0.42, 0.45), grey(0.8, 0.8, 0.82);
  const Eigen::Vector3d eye = cm.pose.translation();
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const Eigen::Vector2d px(x + 0.5, y + 0.5);
      Eigen::Vector3d colour = hall * 0.8;  // walls
      Truth t = kBackground;
      double shade = 1;
      if (const auto g = cm.pixelToGround(px)) {
        if (g->x() < kCarpetEnd && std::abs(g->y()) < kCarpetHalfWidth) {
          t = onLine(*g) ? kLine : kField;
          colour = t == kLine ? paint : field;
          // Grass texture: a little luminance variation.
          colour *= 1 + 0.06 * std::sin(37 * g->x()) * std::cos(23 * g->y());
          if (light.shadow && g->x() > 1.6 && g->x() < 2.4) shade = 0.4;
        } else {
          colour = hall;
        }
      }
      if (robot) {
        const Eigen::Vector3d ray = cm.pixelRay(px);
        const double tHit = (robotAt.x() - eye.x()) / ray.x();
        if (ray.x() > 0 && tHit > 0) {
          const Eigen::Vector3d p = eye + tHit * ray;
          const auto g = cm.pixelToGround(px);
          const bool nearer = !g || (*g - eye.head<2>()).norm() > (p.head<2>() - eye.head<2>()).norm();
          if (nearer && p.z() >= 0 && p.z() <= 0.5 && std::abs(p.y() - robotAt.y()) <= 0.075) {
            t = kRobot;
            colour = p.z() > 0.2 && p.z() < 0.26 ? Eigen::Vector3d(0.15, 0.15, 0.17) : grey;
            shade = 1;
          }
        }
      }
      s.truth.at<std::uint8_t>(y, x) = t;
      cv::Vec3b& out = s.rgb.at<cv::Vec3b>(y, x);
      for (int c = 0; c < 3; ++c)
        out[c] = static_cast<std::uint8_t>(
            std::clamp(colour[c] * light.cast[c] * light.gain * shade * 255 + noise(rng), 0.0, 255.0));
    }
  return s;
}

struct RegionScore {
  long fieldTruth = 0, fieldOk = 0;  // truth field pixels on regions, of them classified field
  long white = 0, whiteOnLine = 0;   // white pixels (on the carpet), of them on a line (+-1 px)
  long lineTruth = 0, lineWhite = 0;  // truth line pixels on regions, of them white
  double fieldCoverage() const { return fieldTruth ? static_cast<double>(fieldOk) / fieldTruth : 1; }
  double whitePrecision() const { return white ? static_cast<double>(whiteOnLine) / white : 1; }
  double lineRecall() const { return lineTruth ? static_cast<double>(lineWhite) / lineTruth : 1; }
};

// Every pixel the scan lines cover, with its region's class: visit(x, y, cls).
template <typename Visit>
void forEachScanPixel(const ScanLineRegions& regions, Visit&& visit) {
  for (const ScanLine& l : regions.vertical)
    for (const ScanRegion& r : l.regions)
      for (int y = r.from; y < r.to; ++y) visit(l.coord, y, r.cls);
  for (const ScanLine& l : regions.horizontal)
    for (const ScanRegion& r : l.regions)
      for (int x = r.from; x < r.to; ++x) visit(x, l.coord, r.cls);
}

RegionScore score(const ScanLineRegions& regions, const cv::Mat& truth) {
  RegionScore s;
  cv::Mat lineNear;  // line pixels dilated by one pixel
  cv::dilate(truth == kLine, lineNear, cv::Mat::ones(3, 3, CV_8U));
  auto visit = [&](int x, int y, RegionClass c) {
    const std::uint8_t t = truth.at<std::uint8_t>(y, x);
    if (t == kField) s.fieldTruth++, s.fieldOk += c == RegionClass::Field;
    if (t == kLine) s.lineTruth++, s.lineWhite += c == RegionClass::White;
    if (c == RegionClass::White && (t == kField || t == kLine)) s.white++, s.whiteOnLine += lineNear.at<std::uint8_t>(y, x) != 0;
  };
  forEachScanPixel(regions, visit);
  return s;
}

// The classes of the scan-line pixels inside a mask (CV_8U, non-zero inside).
struct MaskedClasses {
  long n = 0, field = 0, white = 0;
  double fieldShare() const { return static_cast<double>(field) / std::max(1L, n); }
  double whiteShare() const { return static_cast<double>(white) / std::max(1L, n); }
};
MaskedClasses classesIn(const ScanLineRegions& regions, const cv::Mat& mask) {
  MaskedClasses m;
  forEachScanPixel(regions, [&](int x, int y, RegionClass c) {
    if (!mask.at<std::uint8_t>(y, x)) return;
    ++m.n, m.field += c == RegionClass::Field, m.white += c == RegionClass::White;
  });
  return m;
}

// --- YHS2 -----------------------------------------------------------------------------------

TEST(Yhs, TableMatchesTheDefinition) {
  for (int u = 0; u < 256; u += 5)
    for (int v = 0; v < 256; v += 7) {
      const Yhs c = toYhs(100, static_cast<std::uint8_t>(u), static_cast<std::uint8_t>(v));
      const double hue = std::atan2(v - 128.0, u - 128.0) / (2 * M_PI) * 256;
      const double sat = std::min(255.0, 2 * std::hypot(u - 128.0, v - 128.0));
      EXPECT_LE(hueDistance(c.h, static_cast<int>(std::lround(hue)) & 255), 1) << u << " " << v;
      EXPECT_NEAR(c.s, sat, 1.0) << u << " " << v;
      EXPECT_EQ(c.y, 100);
    }
  // Green, yellow, cyan where the header says.
  EXPECT_LE(hueDistance(toYhs(std::uint8_t{150}, std::uint8_t{85}, std::uint8_t{77}).h, 160), 4);
  EXPECT_EQ(hueDistance(10, 250), 16);
  EXPECT_EQ(hueOffset(250, 10), 16);
  EXPECT_EQ(hueOffset(10, 250), -16);
}

// --- Scan grid ------------------------------------------------------------------------------

TEST(ScanGrid, AdaptsToTheCameraAndStaysBelowTheHorizon) {
  for (double pitch : {5 * kDeg, 15 * kDeg, 30 * kDeg})
    for (double roll : {0.0, 6 * kDeg}) {
      CameraMatrix cm = cameraAt(0.5, pitch);
      cm.pose.linear() = cm.pose.linear() * Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()).toRotationMatrix();
      const ScanGrid g = makeScanGrid(cm, 640, 480);
      ASSERT_FALSE(g.empty());
      ASSERT_EQ(g.xs.size(), g.topY.size());
      ASSERT_EQ(g.ys.size(), g.leftX.size());
      // Nothing above the horizon: every scanned pixel looks at the ground.
      for (std::size_t i = 0; i < g.xs.size(); ++i) {
        EXPECT_FALSE(cm.isAboveHorizon({g.xs[i] + 0.5, g.topY[i] + 0.5})) << g.xs[i];
        EXPECT_LE(g.bottomY[i], 480);
      }
      for (std::size_t i = 0; i < g.ys.size(); ++i) {
        EXPECT_FALSE(cm.isAboveHorizon({g.leftX[i] + 0.5, g.ys[i] + 0.5}));
        EXPECT_FALSE(cm.isAboveHorizon({g.rightX[i] - 0.5, g.ys[i] + 0.5}));
      }
      // At every row, neighbouring vertical lines are no farther apart than the expected
      // width of a field line there (or the finest spacing).
      for (int y = g.horizonY + 2; y < 480; y += 7) {
        if (g.lineWidthPx[y] <= 0) continue;
        std::vector<int> xs;
        for (std::size_t i = 0; i < g.xs.size(); ++i)
          if (g.topY[i] <= y && y < g.bottomY[i]) xs.push_back(g.xs[i]);
        ASSERT_GE(xs.size(), 2u) << "row " << y;
        int widest = 0;
        for (std::size_t i = 1; i < xs.size(); ++i) widest = std::max(widest, xs[i] - xs[i - 1]);
        EXPECT_LE(widest, std::max<double>(g.minSpacing, std::min<double>(32.0, g.lineWidthPx[y])) + 1e-9)
            << "row " << y << " line width " << g.lineWidthPx[y];
      }
      // Neighbouring horizontal lines are no farther apart than the expected width of a field
      // line there, nor (far away, where a line running up the image is short) than 15 cm of
      // ground along the view (plus the finest spacing's worth, 480 / 120 px), or they are
      // within twice the finest spacing.
      ASSERT_EQ(g.extraRow.size(), g.ys.size());
      int extras = 0;
      for (std::size_t i = 1; i < g.ys.size(); ++i) {
        const int y0 = g.ys[i - 1], y1 = g.ys[i];
        extras += g.extraRow[i];
        EXPECT_LE(y1 - y0, std::max(4.0, std::min<double>(32.0, g.lineWidthPx[y1])) + 1) << "row " << y1;
        if (y1 - y0 < 8) continue;
        const auto p0 = cm.pixelToGround({320, y0 + 0.5}), p1 = cm.pixelToGround({320, y1 + 0.5});
        const auto p0b = cm.pixelToGround({320, y0 + 4.5});
        if (!p0 || !p1 || !p0b) continue;
        EXPECT_LE((*p0 - *p1).norm(), 0.15 + (*p0 - *p0b).norm() + 1e-9) << "rows " << y0 << " " << y1;
      }
      if (pitch < 10 * kDeg) {
        EXPECT_GT(extras, 0);
      }
      // The expected width agrees with the projection of a 5 cm line.
      const int row = (g.horizonY + 480) / 2;
      const auto ground = cm.pixelToGround({320, row + 0.5});
      ASSERT_TRUE(ground);
      const double dist = (*ground - cm.pose.translation().head<2>()).norm();
      EXPECT_NEAR(g.lineWidthPx[row], cm.intrinsics.fx * 0.05 / std::hypot(dist, 0.5), 0.25 * g.lineWidthPx[row] + 0.5);
    }
}

TEST(ScanGrid, LooksAboveTheImageAndAtTheOwnFeet) {
  // Looking up: no ground, no lines.
  EXPECT_TRUE(makeScanGrid(cameraAt(0.5, -40 * kDeg), 640, 480).empty());
  // Looking steeply down (a bottom camera at the feet): no sample on the own feet.
  const CameraMatrix down = cameraAt(0.45, 75 * kDeg, 0, 320, 240);
  const ScanGrid g = makeScanGrid(down, 320, 240);
  ASSERT_FALSE(g.empty());
  for (std::size_t i = 0; i < g.xs.size(); ++i)
    for (int y : g.sampleRows) {
      if (y < g.topY[i] || y >= g.bottomY[i]) continue;
      const auto p = down.pixelToGround({g.xs[i] + 0.5, y + 0.5});
      ASSERT_TRUE(p);
      EXPECT_FALSE(p->x() > -0.08 && p->x() < 0.12 && std::abs(p->y()) < 0.11) << g.xs[i] << "," << y;
    }
  // The unknown-pose camera scans the whole image.
  const CameraMatrix unknown = cameraMatrixForUnknownPose(640, 480);
  const ScanGrid u = makeScanGrid(unknown, 640, 480);
  EXPECT_EQ(u.horizonY, 0);
  EXPECT_FALSE(unknown.isAboveHorizon({0.5, 0.5}));
}

// --- Regions on synthetic images ----------------------------------------------------------

TEST(ScanLineRegions, FieldAndLinesUnderEveryLight) {
  const CameraMatrix cm = cameraAt(0.5, 16 * kDeg);
  std::printf("%-7s %8s %8s %8s | %6s %6s %6s %8s\n", "light", "field", "white", "lines", "edgeT", "fieldY", "whiteY",
              "whitePt");
  std::uint64_t seed = 1;
  for (const Light& light : lights()) {
    const Scene s = render(cm, light, seed++);
    const CameraImage img = toCameraImage(s.rgb);
    const FieldSegmentation seg = segmentField(img, cm);
    const RegionScore sc = score(seg.regions, s.truth);
    const FieldColour& fc = seg.regions.fieldColour;
    std::printf("%-7s %8.3f %8.3f %8.3f | %6.1f %6d %6d (%.2f,%.2f)\n", light.name.c_str(), sc.fieldCoverage(),
                sc.whitePrecision(), sc.lineRecall(), fc.edgeThreshold, fc.fieldY, fc.whiteYMin, fc.whiteU, fc.whiteV);
    EXPECT_TRUE(fc.valid) << light.name;
    EXPECT_GE(sc.fieldCoverage(), 0.97) << light.name;
    EXPECT_GE(sc.whitePrecision(), 0.9) << light.name;
    EXPECT_GE(sc.lineRecall(), 0.6) << light.name;
  }
}

// Sunlight through a window clips a stripe of the carpet to the sensor's maximum (R = G = B,
// no colour left; lines inside it vanish), as in real image 00159. The stripe is left
// Unknown -- neither field nor white -- while a line clipped to the same level elsewhere stays
// white, the rest of the field stays field and the field boundary does not move.
TEST(ScanLineRegions, SensorSaturatedStripeIsLeftUnclassified) {
  const CameraMatrix cm = cameraAt(0.5, 16 * kDeg);
  const Scene plain = render(cm, lights()[0], 3);
  const FieldSegmentation before = segmentField(toCameraImage(plain.rgb), cm);
  EXPECT_EQ(before.regions.saturationLevel, -1);
  Scene s = render(cm, lights()[0], 3);
  constexpr int kClip = 213;
  cv::Mat stripe(s.rgb.rows, s.rgb.cols, CV_8U, cv::Scalar(0));
  for (int y = 0; y < s.rgb.rows; ++y)
    for (int x = 0; x < s.rgb.cols; ++x) {
      const auto g = cm.pixelToGround({x + 0.5, y + 0.5});
      if (!g || g->x() >= kCarpetEnd || std::abs(g->y()) >= kCarpetHalfWidth) continue;
      const bool inStripe = g->x() > 1.5 && g->x() < 2.4;
      // The far cross line is painted clipped too: thin, it must stay white.
      const bool clippedLine = s.truth.at<std::uint8_t>(y, x) == kLine && g->x() > 2.9 && g->x() < 3.1;
      if (inStripe) stripe.at<std::uint8_t>(y, x) = 255;
      if (inStripe || clippedLine) s.rgb.at<cv::Vec3b>(y, x) = cv::Vec3b(kClip, kClip, kClip);
    }
  const FieldSegmentation seg = segmentField(toCameraImage(s.rgb), cm);
  EXPECT_NEAR(seg.regions.saturationLevel, kClip, 1);
  long inside = 0, insideUnknown = 0, insideWhite = 0, field = 0, fieldOk = 0, line = 0, lineWhite = 0;
  auto visit = [&](int x, int y, RegionClass c) {
    const std::uint8_t t = s.truth.at<std::uint8_t>(y, x);
    const auto g = cm.pixelToGround({x + 0.5, y + 0.5});
    if (stripe.at<std::uint8_t>(y, x)) {
      // Away from its soft edges (the scan's smoothing blends them with the field).
      if (!g || g->x() < 1.55 || g->x() > 2.35) return;
      ++inside, insideUnknown += c == RegionClass::Unknown, insideWhite += c == RegionClass::White;
    } else if (t == kField && g && (g->x() < 1.4 || g->x() > 2.5)) {
      ++field, fieldOk += c == RegionClass::Field;
    } else if (t == kLine && g && g->x() > 2.9 && g->x() < 3.1) {
      ++line, lineWhite += c == RegionClass::White;
    }
  };
  forEachScanPixel(seg.regions, visit);
  std::printf("stripe: %ld px, %.3f unknown, %.3f white; field outside %.3f; clipped line %.3f white\n", inside,
              double(insideUnknown) / std::max(1L, inside), double(insideWhite) / std::max(1L, inside),
              double(fieldOk) / std::max(1L, field), double(lineWhite) / std::max(1L, line));
  ASSERT_GT(inside, 1000);
  ASSERT_GT(line, 50);
  EXPECT_GE(double(insideUnknown) / inside, 0.95);
  EXPECT_LE(double(insideWhite) / inside, 0.02);
  EXPECT_GE(double(fieldOk) / field, 0.97);
  EXPECT_GE(double(lineWhite) / line, 0.6);
  ASSERT_TRUE(before.boundary.valid);
  ASSERT_TRUE(seg.boundary.valid);
  for (int x = 20; x < s.rgb.cols; x += 40) EXPECT_NEAR(seg.boundary.yAt(x), before.boundary.yAt(x), 3.0) << x;
}

// Sun through a glass wall (real image 00159): between the shadow stripes of the window
// frames, the carpet is washed out to a bright grey with a fifth of the field's chroma --
// brighter and greyer than the field, so "white" by colour, but surfaces tens of centimetres
// across. Lines cannot be that wide: such a white stretch, long along its scan line and wide
// across it (ScanLineRegionizer.h, step 3c), is field. The lines stay white, whether they run
// across the view or away from it, and so do the junctions where they meet.
TEST(ScanLineRegions, WideWashedOutCarpetIsFieldNotLine) {
  const CameraMatrix cm = cameraAt(0.5, 16 * kDeg);
  const Scene plain = render(cm, lights()[0], 9);
  Scene s = render(cm, lights()[0], 9);
  // Sunlit patches on the carpet (robot frame, m), away from the lines.
  struct Patch {
    double x0, x1, y0, y1;
  };
  const std::vector<Patch> patches = {{0.5, 0.95, -0.6, 0.3}, {1.45, 1.8, -0.8, 0.35}, {2.0, 2.6, 1.0, 2.2}};
  cv::Mat inPatch(s.rgb.rows, s.rgb.cols, CV_8U, cv::Scalar(0));
  for (int y = 0; y < s.rgb.rows; ++y)
    for (int x = 0; x < s.rgb.cols; ++x) {
      const auto g = cm.pixelToGround({x + 0.5, y + 0.5});
      if (!g || s.truth.at<std::uint8_t>(y, x) != kField) continue;
      for (const Patch& p : patches)
        if (g->x() > p.x0 && g->x() < p.x1 && g->y() > p.y0 && g->y() < p.y1 && !onLine(*g, 0.1)) {
          inPatch.at<std::uint8_t>(y, x) = 255;
          // Washed out: near the sensor's top, a little green left (a fifth of the field's
          // chroma per luminance).
          s.rgb.at<cv::Vec3b>(y, x) = cv::Vec3b(196, 214, 194);
        }
    }
  const FieldSegmentation seg = segmentField(toCameraImage(s.rgb), cm);
  const FieldSegmentation before = segmentField(toCameraImage(plain.rgb), cm);
  EXPECT_EQ(seg.regions.saturationLevel, -1);  // no clipping: the saturation step plays no part
  const MaskedClasses patch = classesIn(seg.regions, inPatch);
  const RegionScore withPatches = score(seg.regions, s.truth), without = score(before.regions, plain.truth);
  std::printf("patches: %ld px, %.3f field, %.3f white; lines white %.3f (without patches %.3f)\n", patch.n,
              patch.fieldShare(), patch.whiteShare(), withPatches.lineRecall(), without.lineRecall());
  ASSERT_GT(patch.n, 2000);
  EXPECT_GE(patch.fieldShare(), 0.9);
  EXPECT_LE(patch.whiteShare(), 0.05);
  EXPECT_GE(withPatches.lineRecall(), without.lineRecall() - 0.01);
  EXPECT_GE(withPatches.whitePrecision(), 0.85);  // the patches' blurred rims stay white
}

// Near the sensor's clipping level colour is compressed: sunlit carpet whose green channel
// clips keeps only a trace of the field's chroma, and looks white (real image 00159). Where it
// touches something standing on the field (a person's shoes, a robot's feet: here a dark band
// right behind the patch), step 3c cannot tell it from paint by its width. Near-clipped white
// in the field's hue about the white point, more than a line thick (ScanLineRegionizer.h, step
// 3d), is left Unknown -- colour is no evidence there -- while the lines stay white.
TEST(ScanLineRegions, NearClippedFaintlyGreenIsNotWhite) {
  const CameraMatrix cm = cameraAt(0.5, 16 * kDeg);
  constexpr int kClip = 213;
  // The clipped stripe (gives this image's clipping level) and a dark band on the ground.
  auto paint = [&](Scene& s, bool patch, cv::Mat* inPatch) {
    for (int y = 0; y < s.rgb.rows; ++y)
      for (int x = 0; x < s.rgb.cols; ++x) {
        const auto g = cm.pixelToGround({x + 0.5, y + 0.5});
        if (!g || g->x() >= kCarpetEnd || std::abs(g->y()) >= kCarpetHalfWidth) continue;
        if (g->x() > 1.5 && g->x() < 2.4) s.rgb.at<cv::Vec3b>(y, x) = cv::Vec3b(kClip, kClip, kClip);
        const bool across = g->y() > -0.5 && g->y() < 0.4;
        if (across && g->x() > 0.95 && g->x() < 1.05) s.rgb.at<cv::Vec3b>(y, x) = cv::Vec3b(50, 50, 55);
        if (patch && across && g->x() > 0.6 && g->x() <= 0.95) {
          // Washed out: the green channel at the clipping level, a fifth of the field's chroma.
          s.rgb.at<cv::Vec3b>(y, x) = cv::Vec3b(196, kClip, 194);
          if (inPatch && g->x() > 0.63 && g->x() < 0.92 && g->y() > -0.47 && g->y() < 0.37)
            inPatch->at<std::uint8_t>(y, x) = 255;  // away from its blurred rims
        }
      }
  };
  Scene plain = render(cm, lights()[0], 5), s = render(cm, lights()[0], 5);
  cv::Mat inPatch(s.rgb.rows, s.rgb.cols, CV_8U, cv::Scalar(0));
  paint(plain, false, nullptr);
  paint(s, true, &inPatch);
  const FieldSegmentation seg = segmentField(toCameraImage(s.rgb), cm);
  const FieldSegmentation before = segmentField(toCameraImage(plain.rgb), cm);
  EXPECT_NEAR(seg.regions.saturationLevel, kClip, 1);
  const MaskedClasses patch = classesIn(seg.regions, inPatch);
  const RegionScore withPatch = score(seg.regions, s.truth), without = score(before.regions, plain.truth);
  std::printf("near-clipped patch: %ld px, %.3f white, %.3f field; lines white %.3f (without the patch %.3f)\n",
              patch.n, patch.whiteShare(), patch.fieldShare(), withPatch.lineRecall(), without.lineRecall());
  ASSERT_GT(patch.n, 1000);
  EXPECT_LE(patch.whiteShare(), 0.05);
  EXPECT_LE(patch.fieldShare(), 0.05);  // Unknown: colour says nothing there
  EXPECT_GE(withPatch.lineRecall(), without.lineRecall() - 0.01);
}

TEST(ScanLineRegions, RegionsTileTheScannedLines) {
  const CameraMatrix cm = cameraAt(0.5, 20 * kDeg);
  const Scene s = render(cm, lights()[0], 7);
  const CameraImage img = toCameraImage(s.rgb);
  const ScanGrid grid = makeScanGrid(cm, img.width, img.height);
  const ScanLineRegions r = computeScanLineRegions(img, grid, nullptr);
  ASSERT_FALSE(r.vertical.empty());
  ASSERT_FALSE(r.horizontal.empty());
  for (const auto* lines : {&r.vertical, &r.horizontal})
    for (const ScanLine& line : *lines) {
      if (line.regions.empty()) continue;
      EXPECT_EQ(line.regions.front().from, line.start);
      EXPECT_EQ(line.regions.back().to, line.end);
      for (std::size_t k = 0; k < line.regions.size(); ++k) {
        EXPECT_LT(line.regions[k].from, line.regions[k].to);
        EXPECT_NE(line.regions[k].cls, RegionClass::Unknown);
        if (k) {
          EXPECT_EQ(line.regions[k].from, line.regions[k - 1].to);
          EXPECT_NE(line.regions[k].cls, line.regions[k - 1].cls);  // same-class neighbours merged
        }
      }
    }
  // The boundary cut: vertical lines start at the boundary, the cut regions are a subset.
  const FieldBoundary b = detectFieldBoundary(img, r, cm);
  ASSERT_TRUE(b.valid);
  const ScanLineRegions cut = cutAtBoundary(r, b);
  for (const ScanLine& line : cut.vertical) {
    if (line.start < line.end) {
      EXPECT_GE(line.start + 0.5, b.yAt(line.coord + 0.5) - 1e-9);
    }
    if (!line.regions.empty()) {
      EXPECT_EQ(line.regions.front().from, line.start);
    }
  }
  // Scanning with the boundary gives the same picture below it.
  const ScanLineRegions again = computeScanLineRegions(img, grid, &b);
  const RegionScore againScore = score(again, s.truth);
  EXPECT_GE(againScore.fieldCoverage(), 0.97);
  EXPECT_GE(againScore.whitePrecision(), 0.9);
}

TEST(ScanLineRegions, ExtraRowsLeaveTheColourStatisticsAlone) {
  // A flat view: the far rows get extra horizontal lines. Without them, the field colour and
  // the white point are exactly the same, and so are the other lines' regions.
  const CameraMatrix cm = cameraAt(0.5, 6 * kDeg);
  const ScanGrid grid = makeScanGrid(cm, 640, 480);
  ScanGrid coarse = grid;
  coarse.ys.clear(), coarse.leftX.clear(), coarse.rightX.clear(), coarse.xStep.clear(), coarse.extraRow.clear();
  for (std::size_t i = 0; i < grid.ys.size(); ++i)
    if (!grid.extraRow[i]) {
      coarse.ys.push_back(grid.ys[i]), coarse.leftX.push_back(grid.leftX[i]), coarse.rightX.push_back(grid.rightX[i]);
      coarse.xStep.push_back(grid.xStep[i]), coarse.extraRow.push_back(0);
    }
  ASSERT_LT(coarse.ys.size(), grid.ys.size());
  std::uint64_t seed = 3;
  for (const Light& light : lights()) {
    const Scene s = render(cm, light, seed++);
    const CameraImage img = toCameraImage(s.rgb);
    const ScanLineRegions a = computeScanLineRegions(img, grid, nullptr), b = computeScanLineRegions(img, coarse, nullptr);
    const FieldColour &fa = a.fieldColour, &fb = b.fieldColour;
    ASSERT_TRUE(fa.valid) << light.name;
    EXPECT_EQ(fa.fieldY, fb.fieldY) << light.name;
    EXPECT_EQ(fa.hueMin, fb.hueMin) << light.name;
    EXPECT_EQ(fa.hueMax, fb.hueMax) << light.name;
    EXPECT_EQ(fa.satMin, fb.satMin) << light.name;
    EXPECT_EQ(fa.whiteYMin, fb.whiteYMin) << light.name;
    EXPECT_EQ(fa.whiteU, fb.whiteU) << light.name;
    EXPECT_EQ(fa.whiteV, fb.whiteV) << light.name;
    ASSERT_EQ(a.vertical.size(), b.vertical.size());
    for (std::size_t i = 0; i < a.vertical.size(); ++i) {
      ASSERT_EQ(a.vertical[i].regions.size(), b.vertical[i].regions.size()) << light.name << " line " << i;
      for (std::size_t k = 0; k < a.vertical[i].regions.size(); ++k)
        EXPECT_EQ(a.vertical[i].regions[k].cls, b.vertical[i].regions[k].cls) << light.name << " line " << i;
    }
    // Every coarse horizontal line is there with the same regions.
    std::size_t j = 0;
    for (const ScanLine& l : b.horizontal) {
      while (j < a.horizontal.size() && a.horizontal[j].coord != l.coord) ++j;
      ASSERT_LT(j, a.horizontal.size()) << light.name << " row " << l.coord;
      ASSERT_EQ(a.horizontal[j].regions.size(), l.regions.size()) << light.name << " row " << l.coord;
      for (std::size_t k = 0; k < l.regions.size(); ++k) EXPECT_EQ(a.horizontal[j].regions[k].cls, l.regions[k].cls);
    }
  }
}

TEST(ScanLineRegions, NoFieldNoImage) {
  const CameraMatrix cm = cameraAt(0.5, 20 * kDeg);
  // A grey image: no field colour, nothing white, no boundary, no obstacles.
  cv::Mat grey(480, 640, CV_8UC3, cv::Scalar(120, 120, 124));
  const CameraImage img = toCameraImage(grey);
  const FieldSegmentation s = segmentField(img, cm);
  EXPECT_FALSE(s.regions.fieldColour.valid);
  EXPECT_FALSE(s.boundary.valid);
  EXPECT_TRUE(s.obstacles.obstacles.empty());
  for (const ScanLine& l : s.regions.vertical)
    for (const ScanRegion& r : l.regions) EXPECT_EQ(r.cls, RegionClass::Other);
  // An invalid image or one of another size than the grid: nothing, no crash.
  CameraImage broken = img;
  broken.yuyv.resize(100);
  EXPECT_TRUE(computeScanLineRegions(broken, s.grid, nullptr).vertical.empty());
  EXPECT_FALSE(detectFieldBoundary(broken, ScanLineRegions{}, cm).valid);
  EXPECT_TRUE(segmentField(CameraImage{}, cm).regions.vertical.empty());
  const CameraImage small = toCameraImage(cv::Mat(240, 320, CV_8UC3, cv::Scalar(60, 140, 50)));
  EXPECT_TRUE(computeScanLineRegions(small, s.grid, nullptr).vertical.empty());
}

TEST(ScanLineRegions, AnyCameraAnyImage) {
  // Random camera orientations (rolled, upside down, straight down) and random images, both
  // resolutions: results stay inside the image, nothing crashes.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-M_PI, M_PI);
  for (int trial = 0; trial < 60; ++trial) {
    const int w = trial % 2 ? 320 : 640, h = w * 3 / 4;
    CameraMatrix cm = cameraAt(0.3 + 0.1 * (trial % 5), u(rng) / 2, u(rng), w, h);
    cm.pose.linear() = cm.pose.linear() * Eigen::AngleAxisd(trial % 3 ? u(rng) / 8 : u(rng), Eigen::Vector3d::UnitX())
                                              .toRotationMatrix();
    cv::Mat rgb(h, w, CV_8UC3);
    if (trial % 4 == 0) {
      cv::randu(rgb, cv::Scalar::all(0), cv::Scalar::all(256));
    } else {
      rgb.setTo(cv::Scalar(50 + trial, 140, 60));
      for (int k = 0; k < 12; ++k)
        cv::rectangle(rgb, cv::Rect(static_cast<int>(rng() % w), static_cast<int>(rng() % h), 40, 25),
                      cv::Scalar(static_cast<int>(rng() % 256), static_cast<int>(rng() % 256), static_cast<int>(rng() % 256)),
                      -1);
    }
    const FieldSegmentation s = segmentField(toCameraImage(rgb), cm);
    for (const auto* lines : {&s.regions.vertical, &s.regions.horizontal})
      for (const ScanLine& line : *lines)
        for (const ScanRegion& r : line.regions) {
          ASSERT_GE(r.from, 0);
          ASSERT_LE(r.to, lines == &s.regions.vertical ? h : w);
        }
    for (const auto& o : s.obstacles.obstacles) {
      EXPECT_GE(o.left, 0);
      EXPECT_LE(o.right, w);
      EXPECT_GE(o.top, 0);
      EXPECT_LE(o.bottom, h);
    }
  }
}

// --- Boundary and obstacles on synthetic images ---------------------------------------------

// The true boundary at column x: the first row whose truth is carpet (field, line or robot feet).
double trueBoundary(const cv::Mat& truth, const CameraMatrix& cm, int x) {
  for (int y = 0; y < truth.rows; ++y) {
    const auto g = cm.pixelToGround({x + 0.5, y + 0.5});
    if (g && g->x() < kCarpetEnd && std::abs(g->y()) < kCarpetHalfWidth) return y;
  }
  return truth.rows;
}

TEST(FieldBoundary, SyntheticCarpetEdgeUnderEveryLight) {
  for (double yaw : {0.0, 35 * kDeg}) {
    // Yawed: the carpet's corner is in view (two segments).
    const CameraMatrix cm = cameraAt(0.5, 10 * kDeg, yaw);
    std::uint64_t seed = 100;
    for (const Light& light : lights()) {
      const Scene s = render(cm, light, seed++, true);
      const CameraImage img = toCameraImage(s.rgb);
      const FieldSegmentation seg = segmentField(img, cm);
      ASSERT_TRUE(seg.boundary.valid) << light.name;
      std::vector<double> err;
      for (int x = 2; x < 640; x += 8) {
        const double t = trueBoundary(s.truth, cm, x);
        if (t >= 480) continue;
        // The robot hides the edge behind it: skip those columns.
        bool hidden = false;
        for (int y = 0; y < 480 && !hidden; ++y) hidden = s.truth.at<std::uint8_t>(y, x) == kRobot && y <= t + 3;
        if (!hidden) err.push_back(std::abs(seg.boundary.yAt(x + 0.5) - t));
      }
      ASSERT_GT(err.size(), 20u);
      std::sort(err.begin(), err.end());
      const double median = err[err.size() / 2], p90 = err[err.size() * 9 / 10];
      std::printf("yaw %2.0f %-7s boundary error median %.1f px, 90%% %.1f px, %zu points\n", yaw / kDeg,
                  light.name.c_str(), median, p90, seg.boundary.points.size());
      EXPECT_LE(median, 2.0) << light.name;
      EXPECT_LE(p90, 5.0) << light.name;
    }
  }
}

TEST(Obstacles, ARobotOnTheFieldAndNoneWithoutIt) {
  const CameraMatrix cm = cameraAt(0.5, 16 * kDeg);
  std::uint64_t seed = 200;
  for (const Light& light : lights()) {
    for (const Eigen::Vector2d& at : {Eigen::Vector2d(1.5, 0.3), Eigen::Vector2d(2.6, -0.8)}) {
      const Scene s = render(cm, light, seed++, true, at);
      const FieldSegmentation seg = segmentField(toCameraImage(s.rgb), cm);
      const auto foot = cm.projectGround(at);
      ASSERT_TRUE(foot);
      const bool found = std::any_of(seg.obstacles.obstacles.begin(), seg.obstacles.obstacles.end(), [&](const auto& o) {
        return foot->x() >= o.left - 4 && foot->x() <= o.right + 4 && foot->y() >= o.top && foot->y() <= o.bottom + 6;
      });
      EXPECT_TRUE(found) << light.name << " robot at " << at.transpose();
      EXPECT_EQ(seg.obstacles.obstacles.size(), 1u) << light.name;
      for (const auto& o : seg.obstacles.obstacles) {
        EXPECT_NEAR(o.footRobot.x(), at.x(), 0.25 * at.x()) << light.name;
        EXPECT_TRUE(seg.obstacles.contains(0.5 * (o.left + o.right), o.bottom - 1));
      }
    }
    // Lines alone are no obstacle.
    const Scene empty = render(cm, light, seed++, false);
    EXPECT_TRUE(segmentField(toCameraImage(empty.rgb), cm).obstacles.obstacles.empty()) << light.name;
  }
}

// The real images' field colour: real_images_test (RealImages.FieldColourCoversTheMaskedField).

// --- Timing ---------------------------------------------------------------------------------

TEST(Timing, SegmentationOfATopImage) {
  const CameraMatrix cm = cameraAt(0.5, 16 * kDeg);
  const Scene s = render(cm, lights()[0], 5, true);
  const CameraImage img = toCameraImage(s.rgb);
  std::vector<double> ms;
  for (int i = 0; i < 300; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    const FieldSegmentation seg = segmentField(img, cm);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    ASSERT_TRUE(seg.boundary.valid);
  }
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  std::printf("segmentField (grid, regions, boundary, cut, obstacles), 640x480: median %.3f ms over %zu runs\n",
              ms[ms.size() / 2], ms.size());
}

}  // namespace
}  // namespace nao
