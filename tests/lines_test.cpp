// Field lines, the centre circle, intersections, the penalty cross and the goal box side:
// on synthetic images (the ground painted through the camera model, so the truth is exact)
// and on simulated ones (truth from the simulator's field model, never from the detector).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "controllers/StandController.h"
#include "perception/CameraModel.h"
#include "support/StandingCamera.h"
#include "perception/Geometry.h"
#include "perception/RecordedCameraMatrix.h"
#include "perception/vision/ColourTests.h"
#include "perception/vision/FieldBoundaryDetector.h"
#include "perception/vision/ObstacleDetector.h"
#include "perception/vision/ScanGrid.h"
#include "perception/vision/GoalBoxDetector.h"
#include "perception/vision/IntersectionDetector.h"
#include "perception/vision/LineDetector.h"
#include "perception/vision/ScanLineRegionizer.h"
#include "perception/vision/VisionPipeline.h"
#include "robot/Paths.h"
#include "sim/CameraRenderer.h"
#include "sim/GroundTruth.h"
#include "sim/ImageIO.h"
#include "sim/Lighting.h"
#include "sim/World.h"

namespace nao {
namespace {

constexpr double kDeg = M_PI / 180;

using test::standingCamera;

double segmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (a + t * d - p).norm();
}

// The ground as the camera sees it: `paint(p)` (robot frame) says where white paint is;
// everything else below the horizon is grass, above it a grey wall. RGB scaled by `gain`
// and tinted by `tint` (the light), plus sensor noise.
CameraImage syntheticImage(const CameraMatrix& cm, const std::function<bool(const Eigen::Vector2d&)>& paint,
                           double gain = 1.0, const cv::Vec3d& tint = {1, 1, 1}, double noise = 2.0,
                           double blurSigmaPx = 0) {
  const int w = cm.intrinsics.width, h = cm.intrinsics.height;
  cv::Mat rgb(h, w, CV_8UC3);
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0, noise);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      cv::Vec3d c(110, 110, 110);
      // Supersample 2x2 so that thin far lines blend as a camera sees them.
      int white = 0, ground = 0;
      for (double dy : {0.25, 0.75})
        for (double dx : {0.25, 0.75})
          if (const auto g = cm.pixelToGround(Eigen::Vector2d(x + dx, y + dy))) {
            ++ground;
            white += paint(*g);
          }
      if (ground == 4) {
        const double f = white / 4.0;
        c = (1 - f) * cv::Vec3d(40, 140, 45) + f * cv::Vec3d(235, 235, 230);
      }
      for (int k = 0; k < 3; ++k)
        rgb.at<cv::Vec3b>(y, x)[k] = cv::saturate_cast<std::uint8_t>(c[k] * gain * tint[k] + n(rng));
    }
  if (blurSigmaPx > 0) cv::GaussianBlur(rgb, rgb, cv::Size(0, 0), blurSigmaPx);
  return sim::cameraImageFromRgb(rgb, CameraId::Top);
}

// Paint of straight lines (centre segments, robot frame) 5 cm wide.
std::function<bool(const Eigen::Vector2d&)> linesPaint(std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> lines) {
  return [lines](const Eigen::Vector2d& p) {
    for (const auto& [a, b] : lines)
      if (segmentDistance(p, a, b) <= 0.025) return true;
    return false;
  };
}

// Does a detected line lie on the true segment (within 2 deg and 3 cm)?
bool onSegment(const LinesPercept::Line& l, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double tol = 0.03) {
  const Eigen::Vector2d u = (b - a).normalized(), d = (l.to - l.from).normalized();
  return std::abs(u.x() * d.y() - u.y() * d.x()) < std::sin(2 * kDeg) && segmentDistance(l.from, a, b) < tol &&
         segmentDistance(l.to, a, b) < tol;
}

TEST(LineDetector, FindsAStraightLineOnASyntheticImage) {
  const CameraMatrix cm = standingCamera(0, 12);
  const Eigen::Vector2d a(1.6, -1.5), b(1.6, 1.5);
  const VisionResult r = runVision(syntheticImage(cm, linesPaint({{a, b}})), cm);
  ASSERT_EQ(r.lines.lines.size(), 1u);
  EXPECT_TRUE(onSegment(r.lines.lines[0], a, b)) << r.lines.lines[0].from.transpose() << " -> " << r.lines.lines[0].to.transpose();
  EXPECT_GE(r.lines.lines[0].spots.size(), 10u);
  EXPECT_FALSE(r.lines.circle.found);
}

// What the line fit takes, computed as the vision does from the image (without denoising).
struct LineInputs {
  ObstaclesPercept obstacles;
  vision::FieldReference field;
  vision::LineCandidates candidates;
  LineInputs(const CameraImage& image, const CameraMatrix& cm, const vision::LineParams& params) {
    const ScanGrid grid = makeScanGrid(cm, image.width, image.height, params.lineWidth);
    const ScanLineRegions all = computeScanLineRegions(image, grid, nullptr);
    const FieldBoundary boundary = detectFieldBoundary(image, all, cm);
    const ScanLineRegions regions = cutAtBoundary(all, boundary);
    obstacles = detectObstacles(image, regions, boundary, cm);
    field = vision::FieldReference::from(regions);
    candidates = vision::findLineCandidates(image, regions, field, obstacles, cm, params);
  }
};

// The spots of a soft-edged line (defocus, as real frames show lines 2-5 m away) as the line
// detector finds them: median thickness over expected width and median distance from the
// true line's image.
struct SoftLineSpots {
  int spots = 0;
  double thicknessRatio = 0, offsetPx = 0;
};
SoftLineSpots softLineSpots(const vision::LineParams& params) {
  const CameraMatrix cm = standingCamera(0, 12);
  const Eigen::Vector2d a(1.3, -1.5), b(1.3, 1.5);
  const CameraImage image = syntheticImage(cm, linesPaint({{a, b}}), 1.0, {1, 1, 1}, 2.0, 2.2);
  const vision::LineCandidates c = LineInputs(image, cm, params).candidates;
  const Eigen::Vector2d p = *cm.projectGround(a), q = *cm.projectGround(b), d = (q - p).normalized();
  std::vector<double> ratio, offset;
  for (const auto& s : c.spots) {
    if (!s.vertical) continue;
    ratio.push_back(s.thicknessPx / s.expectedPx);
    offset.push_back(std::abs(d.x() * (s.image.y() - p.y()) - d.y() * (s.image.x() - p.x())));
  }
  SoftLineSpots out;
  out.spots = static_cast<int>(ratio.size());
  if (ratio.empty()) return out;
  std::nth_element(ratio.begin(), ratio.begin() + ratio.size() / 2, ratio.end());
  std::nth_element(offset.begin(), offset.begin() + offset.size() / 2, offset.end());
  out.thicknessRatio = ratio[ratio.size() / 2];
  out.offsetPx = offset[offset.size() / 2];
  return out;
}

TEST(LineDetector, SoftEdgedLineSpotsAreMeasuredAtHalfContrast) {
  const SoftLineSpots measured = softLineSpots({});
  vision::LineParams regionsOnly;
  regionsOnly.halfContrastFactor = 1e9;
  const SoftLineSpots runs = softLineSpots(regionsOnly);
  ASSERT_GE(measured.spots, 30);
  // The blur widens the white runs well beyond a line's width; at half contrast the spots are
  // about as thick as the line (a Gaussian of 2.2 px widens the line by little at half contrast).
  EXPECT_GT(runs.thicknessRatio, 1.4) << "the test's blur no longer widens the runs";
  EXPECT_LT(measured.thicknessRatio, 1.25);
  EXPECT_GT(measured.thicknessRatio, 0.8);
  EXPECT_LT(measured.offsetPx, 0.5);
}

// The lines the detector reports on an image, with these parameters.
std::vector<LinesPercept::Line> linesWith(const CameraImage& image, const CameraMatrix& cm, const vision::LineParams& params) {
  const LineInputs in(image, cm, params);
  return vision::fitLines(in.candidates, {}, image, in.field, in.obstacles, cm, params);
}

// Real tape is bent: the goal box's front line on these real frames bows by 1.5-2.5 px over
// 450-570 px, so the vision sees it as two straight pieces meeting at a kink of about 1.3 deg,
// and the shorter piece's direction, extrapolated over the longer one, misses its far end by
// 4-8 px. Both pieces are well measured and the merged fit holds every spot: one line, within
// 3 px and 2 deg of the labelled ends. Without the kink allowance (mergeKinkDeg 0) the front
// line stays in pieces. (On synthetic images a bend of this size merges either way: pieces of a
// clean line extrapolate well.)
TEST(LineDetector, ABentRealLineIsOneLine) {
  for (const char* stem : {"1687083883", "1687086249"}) {
    const std::string dir = std::string(NAO_SHARED_DIR) + "/data/real-goalbox-images/";
    const RecordedCameraMatrix rec = RecordedCameraMatrix::read(dir + stem + ".json");
    const CameraImage image = sim::readImage(dir + stem + ".jpg", 0, 0, rec.camera);
    const CameraMatrix cm = rec.forImage(image.width, image.height);
    const auto label = std::find_if(rec.lines.begin(), rec.lines.end(), [](const LabelledLine& l) { return l.name == "goal_box_line"; });
    ASSERT_NE(label, rec.lines.end()) << stem;
    auto found = [&](const std::vector<LinesPercept::Line>& ls) {
      return std::any_of(ls.begin(), ls.end(), [&](const LinesPercept::Line& l) {
        const Eigen::Vector2d d = (l.imageTo - l.imageFrom).normalized(), u = (label->b - label->a).normalized();
        auto off = [&](const Eigen::Vector2d& p) { return std::abs(d.x() * (p.y() - l.imageFrom.y()) - d.y() * (p.x() - l.imageFrom.x())); };
        return std::abs(d.x() * u.y() - d.y() * u.x()) < std::sin(2 * kDeg) && off(label->a) < 3 && off(label->b) < 3;
      });
    };
    vision::LineParams straightOnly;
    straightOnly.mergeKinkDeg = 0;
    EXPECT_FALSE(found(linesWith(image, cm, straightOnly))) << stem << ": the line no longer comes in pieces here";
    EXPECT_TRUE(found(linesWith(image, cm, {}))) << stem;
  }
}

TEST(LineDetector, NothingOnPlainGrass) {
  const CameraMatrix cm = standingCamera(0, 12);
  const VisionResult r = runVision(syntheticImage(cm, [](const Eigen::Vector2d&) { return false; }), cm);
  EXPECT_TRUE(r.lines.lines.empty());
  EXPECT_FALSE(r.lines.circle.found);
  EXPECT_FALSE(r.ball.seen);
}

TEST(LineDetector, SameLinesInDimAndInWarmLight) {
  // Nothing is tuned for the light: a quarter of the light, or orange light, finds the same.
  const CameraMatrix cm = standingCamera(20, 10);
  const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> truth = {{{1.4, 0.3}, {3.4, 0.3}},
                                                                          {{1.4, 0.3}, {1.4, 2.3}}};
  for (const auto& [gain, tint] : std::vector<std::pair<double, cv::Vec3d>>{{1.0, {1, 1, 1}},
                                                                          {0.25, {1, 1, 1}},
                                                                          {0.9, {1.0, 0.72, 0.42}}}) {
    SCOPED_TRACE(gain);
    const VisionResult r = runVision(syntheticImage(cm, linesPaint(truth), gain, tint, gain < 0.5 ? 1.5 : 2.0), cm);
    for (const auto& [a, b] : truth) {
      bool found = false;
      for (const auto& l : r.lines.lines) found = found || onSegment(l, a, b, 0.04);
      EXPECT_TRUE(found) << a.transpose() << " -> " << b.transpose();
    }
    for (const auto& l : r.lines.lines) {
      bool ok = false;
      for (const auto& [a, b] : truth) ok = ok || onSegment(l, a, b, 0.05);
      EXPECT_TRUE(ok) << "false line " << l.from.transpose() << " -> " << l.to.transpose();
    }
    // The corner: both lines end there.
    ASSERT_FALSE(r.lines.intersections.empty());
    EXPECT_EQ(r.lines.intersections[0].type, LinesPercept::Intersection::Type::L);
    EXPECT_LT((r.lines.intersections[0].position - Eigen::Vector2d(1.4, 0.3)).norm(), 0.1);
  }
}

TEST(WhiteTest, PaintOnGrassPassesGrassDoesNot) {
  const CameraMatrix cm = standingCamera(0, 12);
  const CameraImage img = syntheticImage(cm, linesPaint({{{1.6, -1.5}, {1.6, 1.5}}}));
  vision::FieldReference field;
  field.valid = true;
  // Grass (40, 140, 45) in YUV: hue about -130 deg.
  const double hue = std::atan2(-47.0, -31.0);
  field.hueMin = hue - 0.3, field.hueMax = hue + 0.3;
  field.satMin = 30, field.yMin = 50, field.yMax = 130, field.fieldY = 100;
  field.fieldRelSatPerY = 0.5;
  const auto onLine = vision::whiteRatio(img, field, cm, *cm.projectGround({1.6, -0.4}), *cm.projectGround({1.6, 0.4}), 0.05);
  const auto beside = vision::whiteRatio(img, field, cm, *cm.projectGround({1.9, -0.4}), *cm.projectGround({1.9, 0.4}), 0.05);
  ASSERT_TRUE(onLine && beside);
  EXPECT_GT(*onLine, 0.95);
  EXPECT_LT(*beside, 0.05);
}

TEST(CircleDetector, FindsTheCentreCircleAndReportsNoLinesOnIt) {
  const CameraMatrix cm = standingCamera(0, 18);
  const Eigen::Vector2d centre(1.7, 0.1);
  const VisionResult r = runVision(syntheticImage(cm, [&](const Eigen::Vector2d& p) {
                                     return std::abs((p - centre).norm() - 0.75) <= 0.025;
                                   }),
                                   cm);
  ASSERT_TRUE(r.lines.circle.found);
  EXPECT_LT((r.lines.circle.centre - centre).norm(), 0.05);
  EXPECT_TRUE(r.lines.lines.empty()) << r.lines.lines.size() << " lines on the circle";
}

// A detected line as the line detector would report it: ground ends and their pixels.
LinesPercept::Line groundLine(const CameraMatrix& cm, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  LinesPercept::Line l;
  l.from = a, l.to = b;
  l.imageFrom = *cm.projectGround(a), l.imageTo = *cm.projectGround(b);
  return l;
}

TEST(IntersectionDetector, TypesLTAndXOnTheGround) {
  const CameraMatrix cm = standingCamera(0, 15);
  auto line = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return groundLine(cm, a, b); };
  using T = LinesPercept::Intersection::Type;
  const ObstaclesPercept none;
  // L: both end at (1.5, 0).
  auto xs = vision::detectIntersections({line({1.5, 0}, {2.5, 0}), line({1.5, 0}, {1.5, 0.8})}, cm, none);
  ASSERT_EQ(xs.size(), 1u);
  EXPECT_EQ(xs[0].type, T::L);
  // T: the second passes through.
  xs = vision::detectIntersections({line({1.5, 0}, {2.5, 0}), line({1.5, -0.6}, {1.5, 0.6})}, cm, none);
  ASSERT_EQ(xs.size(), 1u);
  EXPECT_EQ(xs[0].type, T::T);
  EXPECT_LT((xs[0].position - Eigen::Vector2d(1.5, 0)).norm(), 1e-6);
  // X: both pass through.
  xs = vision::detectIntersections({line({1.2, 0}, {2.2, 0}), line({1.6, -0.6}, {1.6, 0.6})}, cm, none);
  ASSERT_EQ(xs.size(), 1u);
  EXPECT_EQ(xs[0].type, T::X);
  // Parallel lines do not intersect; lines far apart do not either.
  EXPECT_TRUE(vision::detectIntersections({line({1.2, 0}, {2.2, 0}), line({1.2, 0.5}, {2.2, 0.5})}, cm, none).empty());
  EXPECT_TRUE(vision::detectIntersections({line({1.2, 0}, {1.6, 0}), line({2.4, -0.6}, {2.4, 0.6})}, cm, none).empty());
}

// A T whose crossbar the line detector found only on one side looks like an L; the image
// shows the paint going on past the point, so it is not called one. A real L is still an L.
TEST(IntersectionDetector, AMissedPieceBeyondAnEndIsNoEnd) {
  const CameraMatrix cm = standingCamera(0, 15);
  auto line = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return groundLine(cm, a, b); };
  const ObstaclesPercept none;
  // The paint: a T at (1.5, 0) -- the stem along x from the crossbar, the crossbar along y.
  const CameraImage tImage = syntheticImage(cm, linesPaint({{{1.5, 0}, {2.5, 0}}, {{1.5, -0.6}, {1.5, 0.6}}}));
  const vision::FieldReference field = vision::FieldReference::from(segmentField(tImage, cm).regions);
  ASSERT_TRUE(field.valid);
  // Detected: the stem and only the crossbar's left half (ending at the T).
  const std::vector<LinesPercept::Line> seen = {line({1.5, 0}, {2.5, 0}), line({1.5, 0}, {1.5, 0.6})};
  const auto blind = vision::detectIntersections(seen, cm, none);
  ASSERT_EQ(blind.size(), 1u);
  EXPECT_EQ(blind[0].type, LinesPercept::Intersection::Type::L);  // from the lines alone
  EXPECT_TRUE(vision::detectIntersections(seen, cm, none, {}, &tImage, &field).empty());
  // The same two lines where the paint is an L: an L.
  const CameraImage lImage = syntheticImage(cm, linesPaint({{{1.5, 0}, {2.5, 0}}, {{1.5, 0}, {1.5, 0.6}}}));
  const vision::FieldReference lField = vision::FieldReference::from(segmentField(lImage, cm).regions);
  const auto xs = vision::detectIntersections(seen, cm, none, {}, &lImage, &lField);
  ASSERT_EQ(xs.size(), 1u);
  EXPECT_EQ(xs[0].type, LinesPercept::Intersection::Type::L);
}

TEST(GoalBoxDetector, AShortLineJoiningTwoLongLines) {
  auto line = [](Eigen::Vector2d a, Eigen::Vector2d b) {
    LinesPercept::Line l;
    l.imageFrom = a, l.imageTo = b;
    return l;
  };
  // Two long lines running up the image, a short one across between them (image only).
  std::vector<LinesPercept::Line> lines = {line({100, 460}, {300, 120}), line({420, 460}, {360, 120}),
                                           line({242, 220}, {378, 222})};
  auto g = detectGoalBoxSide(lines, 640, 480);
  ASSERT_TRUE(g.found);
  EXPECT_EQ(g.shortLine, 2);
  EXPECT_TRUE((g.longLine1 == 0 && g.longLine2 == 1) || (g.longLine1 == 1 && g.longLine2 == 0));
  // A short line that reaches only one long line is no goal box side.
  lines[2] = line({242, 220}, {320, 221});
  EXPECT_FALSE(detectGoalBoxSide(lines, 640, 480).found);
  // Nor is one cut by the image border.
  lines[2] = line({0, 220}, {378, 222});
  EXPECT_FALSE(detectGoalBoxSide(lines, 640, 480).found);
}

TEST(PenaltyMarkDetector, FindsTheCrossButNotTheCentreMarkOnALine) {
  const CameraMatrix cm = standingCamera(0, 15);
  const Eigen::Vector2d cross(1.8, 0.2);
  auto crossPaint = [&](const Eigen::Vector2d& c) {
    return [c](const Eigen::Vector2d& p) {
      const Eigen::Vector2d d = (p - c).cwiseAbs();
      return (d.x() <= 0.05 && d.y() <= 0.025) || (d.y() <= 0.05 && d.x() <= 0.025);
    };
  };
  VisionResult r = runVision(syntheticImage(cm, crossPaint(cross)), cm);
  ASSERT_TRUE(r.lines.penaltyMark.has_value());
  EXPECT_LT((*r.lines.penaltyMark - cross).norm(), 0.05);
  EXPECT_TRUE(r.lines.lines.empty());
  EXPECT_FALSE(r.ball.seen) << "the cross is no ball";
  // The same cross on a line (the centre mark on the halfway line) is no penalty mark.
  const auto onLine = crossPaint(cross);
  const auto line = linesPaint({{{cross.x(), -1.5}, {cross.x(), 1.5}}});
  r = runVision(syntheticImage(cm, [&](const Eigen::Vector2d& p) { return onLine(p) || line(p); }), cm);
  EXPECT_FALSE(r.lines.penaltyMark.has_value());
}

// A simulated robot at the calibration position (side line, in line with its penalty mark,
// head towards the goal box): the lines found match the true visible ones and the goal box
// is seen from the side.
TEST(LinesSimulated, CalibrationViewMatchesTheFieldModel) {
  sim::SceneSpec spec;
  spec.field = FieldDimensions::load(dataPath("config/field_dimensions.json"));
  spec.robots = {Eigen::Vector3d(-3.2, -3.0, 90 * kDeg)};
  sim::World world(spec, 1);
  JointArray posture = StandController::standPosture();
  posture[HeadYaw] = 35 * kDeg;
  posture[HeadPitch] = 12 * kDeg;
  world.placeRobot(0, spec.robots[0], posture);
  sim::CameraRenderer renderer(world.model());
  std::mt19937_64 rng(3);
  int goalBoxes = 0;
  for (const char* preset : {"default", "dark", "warm"}) {
    SCOPED_TRACE(preset);
    const sim::Lighting lighting = sim::Lighting::parse(preset, dataPath("config/lighting.json"));
    const CameraImage img = renderer.renderImage(world.model(), world.data(), world.cameraIndex(0, CameraId::Top), 640, 480,
                                                 lighting, CameraId::Top, 0, rng, ExposureWeights{});
    const SensorFrame s = world.sensors(0);
    const CameraMatrix cm = computeCameraMatrix(s.joints.position, s.inertial.angle, CameraId::Top, CameraCalibration{},
                                                CameraIntrinsics::nominal(CameraId::Top));
    const VisionResult r = runVision(img, cm);
    const Eigen::Vector3d pose = world.robotPose(0);
    const auto truth = sim::visibleFeatures(world, 0, CameraId::Top, 4.0);
    int wanted = 0, found = 0;
    for (const auto& tl : truth.lines) {
      if (tl.visibleLength < 0.5) continue;
      ++wanted;
      const FieldLine& fl = world.field().lines[tl.index];
      for (const auto& l : r.lines.lines) {
        const Eigen::Vector2d a = robotToField(l.from, pose), b = robotToField(l.to, pose);
        const Eigen::Vector2d u = (fl.to - fl.from).normalized(), d = (b - a).normalized();
        if (std::abs(u.x() * d.y() - u.y() * d.x()) < std::sin(5 * kDeg) && segmentDistance(a, fl.from, fl.to) < 0.1 &&
            segmentDistance(b, fl.from, fl.to) < 0.1) {
          ++found;
          break;
        }
      }
    }
    EXPECT_GE(wanted, 3);
    EXPECT_GE(found, wanted - 1) << found << " of " << wanted;
    for (const auto& l : r.lines.lines) {
      const Eigen::Vector2d a = robotToField(l.from, pose), b = robotToField(l.to, pose);
      double best = 1e9;
      for (const auto& fl : world.field().lines)
        best = std::min(best, std::max(segmentDistance(a, fl.from, fl.to), segmentDistance(b, fl.from, fl.to)));
      EXPECT_LT(best, 0.1) << "line " << a.transpose() << " -> " << b.transpose() << " lies on no field line";
    }
    goalBoxes += r.lines.goalBoxSide.found;
  }
  // The goal box's front line, 4.1 m away, is a 3 px line at the line detector's limit (its
  // direction on the ground 2.0-2.1 deg uncertain against the 2 deg accepted): a change of 1-2
  // grey levels (the white balance's, 2026-12-06) decides whether it, and so the goal box, is
  // found in one of the three lights.
  EXPECT_GE(goalBoxes, 2);
}

}  // namespace
}  // namespace nao
