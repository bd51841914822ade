// Each module of the camera pipeline alone (tests/support/ModuleHarness.h), on synthetic
// images whose truth is exact (ground paint and spheres drawn through the camera model,
// tests/support/SyntheticScene.h): the module's inputs are fixed (from the modules before it,
// or by hand) and its output is checked against the painted truth, never against the module.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include <opencv2/core.hpp>

#include "perception/vision/CameraPipeline.h"
#include "perception/vision/modules/BallPerceptor.h"
#include "perception/vision/modules/CameraPerceptsProvider.h"
#include "perception/vision/modules/CirclePerceptor.h"
#include "perception/vision/modules/FieldBoundaryProvider.h"
#include "perception/vision/modules/FieldColourReferenceProvider.h"
#include "perception/vision/modules/GoalBoxSidePerceptor.h"
#include "perception/vision/modules/IntersectionPerceptor.h"
#include "perception/vision/modules/LinePerceptor.h"
#include "perception/vision/modules/LineSpotProvider.h"
#include "perception/vision/modules/ObstaclePerceptor.h"
#include "perception/vision/modules/PenaltyMarkPerceptor.h"
#include "perception/vision/modules/ScanGridProvider.h"
#include "perception/vision/modules/ScanLineRegionCutter.h"
#include "perception/vision/modules/ScanLineRegionProvider.h"
#include "tests/support/StandingCamera.h"
#include "tests/support/SyntheticScene.h"
#include "sim/ImageIO.h"
#include "tests/support/ModuleHarness.h"

namespace nao {
namespace {

using test::standingCamera;
using testing::ModuleHarness;
using Paint = std::function<bool(const Eigen::Vector2d&)>;
using Segment = std::pair<Eigen::Vector2d, Eigen::Vector2d>;

double segmentDistance(const Eigen::Vector2d& p, const Segment& s) {
  const Eigen::Vector2d d = s.second - s.first;
  const double t = std::clamp((p - s.first).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (s.first + t * d - p).norm();
}

Paint segmentsPaint(const std::vector<Segment>& segments) {
  return [segments](const Eigen::Vector2d& p) {
    return std::any_of(segments.begin(), segments.end(),
                       [&](const Segment& s) { return segmentDistance(p, s) <= 0.025; });
  };
}

// A T at (1.5, 0): the stem along x, the crossbar along y.
const std::vector<Segment> kT = {{{1.5, 0}, {2.5, 0}}, {{1.5, -0.6}, {1.5, 0.6}}};

// Runs the camera pipeline on the image, so a module's inputs can be taken from the modules
// before it.
struct Upstream {
  CameraPipeline pipeline;
  Upstream(const CameraImage& image, const CameraMatrix& cm) : pipeline(image.camera, VisionGeometry{}) {
    pipeline.process(image, cm);
  }
  template <class... T>
  void fixInto(ModuleHarness& h) const {
    (h.fix(pipeline.get<T>()), ...);
  }
};

template <class M>
ModuleHarness harness() {
  return ModuleHarness::make<M>(ModuleContext{});
}

TEST(ScanGridProvider, LinesBelowTheHorizonSizedByTheLineWidth) {
  const CameraMatrix cm = standingCamera(0, 5);
  CameraImage image;
  image.width = 640, image.height = 480;
  image.yuyv.assign(640 * 480 * 2, 128);
  ModuleHarness h = harness<modules::ScanGridProvider>();
  h.fix(image).fix(cm).fix(VisionGeometry{}).run();
  const ScanGrid grid = h.get<ScanGrid>();
  EXPECT_EQ(grid.width, 640);
  EXPECT_EQ(grid.height, 480);
  ASSERT_FALSE(grid.empty());
  EXPECT_GT(grid.horizonY, 0) << "pitched 5 deg, the horizon is in the image";
  EXPECT_TRUE(std::is_sorted(grid.xs.begin(), grid.xs.end()));
  for (std::size_t i = 0; i < grid.xs.size(); ++i) {
    ASSERT_GE(grid.xs[i], 0);
    ASSERT_LT(grid.xs[i], 640);
    // Every scanned pixel sees the ground.
    EXPECT_TRUE(cm.pixelToGround(Eigen::Vector2d(grid.xs[i] + 0.5, grid.topY[i] + 0.5)).has_value()) << grid.xs[i];
  }
  VisionGeometry wide;
  wide.lineWidth = 0.15;
  h.fix(wide).run();
  // The expected line width in the image follows the geometry's line width.
  const ScanGrid& wideGrid = h.get<ScanGrid>();
  int rows = 0;
  for (int y = grid.horizonY + 20; y < 480; y += 20, ++rows)
    EXPECT_NEAR(wideGrid.lineWidthPx[y] / grid.lineWidthPx[y], 3.0, 0.1) << "row " << y;
  EXPECT_GT(rows, 5);
}

TEST(ScanLineRegionProvider, WhiteWherePaintIsFieldElsewhere) {
  const CameraMatrix cm = standingCamera(0, 15);
  const CameraImage image = test::syntheticImage(cm, {}, segmentsPaint(kT));
  const Upstream up(image, cm);
  ModuleHarness h = harness<modules::ScanLineRegionProvider>();
  up.fixInto<CameraImage, DenoisedImage, ScanGrid>(h);
  h.run();
  const UncutScanLineRegions& regions = h.get<UncutScanLineRegions>();
  ASSERT_TRUE(regions.fieldColour.valid);
  int white = 0, whiteOnPaint = 0, field = 0, fieldOnPaint = 0;
  for (const ScanLine& line : regions.vertical)
    for (const ScanRegion& r : line.regions) {
      const auto g = cm.pixelToGround(Eigen::Vector2d(line.coord + 0.5, 0.5 * (r.from + r.to)));
      if (!g) continue;
      const bool onPaint =
          std::any_of(kT.begin(), kT.end(), [&](const Segment& s) { return segmentDistance(*g, s) < 0.06; });
      if (r.cls == RegionClass::White) white++, whiteOnPaint += onPaint;
      if (r.cls == RegionClass::Field && r.to - r.from > 6) field++, fieldOnPaint += onPaint;
    }
  EXPECT_GE(white, 10);
  EXPECT_GE(whiteOnPaint, 0.9 * white) << whiteOnPaint << " of " << white << " white regions on the paint";
  EXPECT_GE(field, 20);
  EXPECT_LE(fieldOnPaint, 0.05 * field);
}

// Carpet up to x = edgeX (robot frame) before a grey wall: the field boundary's truth.
constexpr double kEdgeX = 3.0;
CameraImage carpetImage(const CameraMatrix& cm) {
  return test::syntheticImage(cm, {}, test::kNoPaint, {}, CameraId::Top, 0,
                              [](const Eigen::Vector2d& g) { return g.x() < kEdgeX; });
}

TEST(FieldBoundaryProvider, AtTheCarpetsEdge) {
  const CameraMatrix cm = standingCamera(0, 2);
  const CameraImage image = carpetImage(cm);
  const Upstream up(image, cm);
  ModuleHarness h = harness<modules::FieldBoundaryProvider>();
  up.fixInto<CameraImage, UncutScanLineRegions, CameraMatrix>(h);
  h.run();
  const FieldBoundary& b = h.get<FieldBoundary>();
  ASSERT_TRUE(b.valid);
  std::vector<double> err;
  for (int x = 4; x < 640; x += 16) {
    int truth = 480;  // the first row of carpet in this column
    for (int y = 0; y < 480 && truth == 480; ++y)
      if (const auto g = cm.pixelToGround(Eigen::Vector2d(x + 0.5, y + 0.5)); g && g->x() < kEdgeX) truth = y;
    err.push_back(std::abs(b.yAt(x + 0.5) - truth));
  }
  std::sort(err.begin(), err.end());
  EXPECT_LE(err[err.size() / 2], 3.0);
  EXPECT_LE(err[err.size() * 9 / 10], 6.0);
}

TEST(ScanLineRegionCutter, NothingAboveTheBoundary) {
  const CameraMatrix cm = standingCamera(0, 2);
  const CameraImage image = carpetImage(cm);
  const Upstream up(image, cm);
  ModuleHarness h = harness<modules::ScanLineRegionCutter>();
  up.fixInto<UncutScanLineRegions, FieldBoundary>(h);
  h.run();
  const FieldBoundary& boundary = up.pipeline.get<FieldBoundary>();
  ASSERT_TRUE(boundary.valid);
  const ScanLineRegions& cut = h.get<ScanLineRegions>();
  int below = 0;
  for (const ScanLine& line : cut.vertical)
    for (const ScanRegion& r : line.regions) {
      EXPECT_GE(r.from, boundary.yAt(line.coord + 0.5) - 1.0) << "x " << line.coord;
      ++below;
    }
  EXPECT_GT(below, 50);
  // The uncut regions reach above it (the wall).
  int above = 0;
  for (const ScanLine& line : up.pipeline.get<UncutScanLineRegions>().vertical)
    for (const ScanRegion& r : line.regions) above += r.from < boundary.yAt(line.coord + 0.5) - 1.0;
  EXPECT_GT(above, 0);
}

// Grass to the horizon with a grey box 0.15 m wide and 0.5 m tall standing at `at` (a robot,
// as in scan_regions_test), or without it.
CameraImage robotImage(const CameraMatrix& cm, const Eigen::Vector2d& at, bool robot) {
  const int w = cm.intrinsics.width, h = cm.intrinsics.height;
  cv::Mat rgb(h, w, CV_8UC3);
  const Eigen::Vector3d eye = cm.pose.translation();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Eigen::Vector2d px(x + 0.5, y + 0.5);
      Eigen::Vector3d colour(0.34, 0.34, 0.36);  // the hall
      const auto g = cm.pixelToGround(px);
      if (g) colour = Eigen::Vector3d(0.22, 0.55, 0.20) * (1 + 0.06 * std::sin(37 * g->x()) * std::cos(23 * g->y()));
      const Eigen::Vector3d ray = cm.pixelRay(px);
      const double t = (at.x() - eye.x()) / ray.x();
      if (robot && ray.x() > 0 && t > 0) {
        const Eigen::Vector3d p = eye + t * ray;
        const bool nearer = !g || (*g - eye.head<2>()).norm() > (p.head<2>() - eye.head<2>()).norm();
        if (nearer && p.z() >= 0 && p.z() <= 0.5 && std::abs(p.y() - at.y()) <= 0.075)
          colour = p.z() > 0.2 && p.z() < 0.26 ? Eigen::Vector3d(0.15, 0.15, 0.17) : Eigen::Vector3d(0.8, 0.8, 0.82);
      }
      for (int c = 0; c < 3; ++c) rgb.at<cv::Vec3b>(y, x)[c] = cv::saturate_cast<std::uint8_t>(colour[c] * 255);
    }
  return sim::cameraImageFromRgb(rgb, CameraId::Top);
}

TEST(ObstaclePerceptor, ARobotStandingOnTheFieldAndNothingOnBareGrass) {
  const CameraMatrix cm = standingCamera(0, 16);
  const Eigen::Vector2d at(1.5, 0.3);
  for (const bool robot : {true, false}) {
    const CameraImage image = robotImage(cm, at, robot);
    const Upstream up(image, cm);
    ModuleHarness h = harness<modules::ObstaclePerceptor>();
    up.fixInto<CameraImage, ScanLineRegions, FieldBoundary, CameraMatrix>(h);
    h.run();
    const ObstaclesPercept& o = h.get<ObstaclesPercept>();
    if (!robot) {
      EXPECT_TRUE(o.obstacles.empty());
      continue;
    }
    ASSERT_EQ(o.obstacles.size(), 1u);
    EXPECT_NEAR(o.obstacles[0].footRobot.x(), at.x(), 0.25 * at.x());
    const auto foot = cm.projectGround(at);
    ASSERT_TRUE(foot);
    EXPECT_TRUE(foot->x() >= o.obstacles[0].left - 4 && foot->x() <= o.obstacles[0].right + 4);
    EXPECT_TRUE(foot->y() >= o.obstacles[0].top && foot->y() <= o.obstacles[0].bottom + 6);
  }
}

TEST(FieldColourReferenceProvider, GrassIsFieldAndPaintIsWhite) {
  const CameraMatrix cm = standingCamera(0, 15);
  const CameraImage image = test::syntheticImage(cm, {}, segmentsPaint(kT));
  const Upstream up(image, cm);
  ModuleHarness h = harness<modules::FieldColourReferenceProvider>();
  up.fixInto<ScanLineRegions>(h);
  h.run();
  const FieldColourReference& f = h.get<FieldColourReference>();
  ASSERT_TRUE(f.valid);
  // The colours the scene was painted with, as the image holds them.
  const auto at = [&](const Eigen::Vector2d& ground) {
    const Eigen::Vector2d px = *cm.projectGround(ground);
    return vision::sampleColour(image, px.x(), px.y());
  };
  EXPECT_TRUE(f.isField(at({1.2, 0.5})));
  EXPECT_FALSE(f.isField(at({2.0, 0.0})));
  EXPECT_GT(at({2.0, 0.0}).y, f.yMax);
}

TEST(BallPerceptor, FindsTheBallWhereItLies) {
  const CameraMatrix cm = standingCamera(0, 15);
  const Eigen::Vector2d ball(1.3, 0.15);
  const CameraImage image =
      test::syntheticImage(cm,
                           {{Eigen::Vector3d(ball.x(), ball.y(), test::kSyntheticBallRadius),
                             test::kSyntheticBallRadius, test::soccerBall(Eigen::Matrix3d::Identity())}},
                           test::kNoPaint);
  const Upstream up(image, cm);
  ModuleHarness h = harness<modules::BallPerceptor>();
  up.fixInto<CameraImage, DenoisedImage, ScanLineRegions, FieldColourReference, ObstaclesPercept, CameraMatrix,
                   VisionGeometry>(h);
  h.fix(OwnBody{}).run();
  const BallPercept b = h.get<BallPercept>();
  ASSERT_TRUE(b.seen);
  EXPECT_LT((b.position - ball).norm(), 0.05 * ball.norm());
  EXPECT_LT((b.image - *cm.project(Eigen::Vector3d(ball.x(), ball.y(), test::kSyntheticBallRadius))).norm(), 3.0);
  // The robot's own body in front of it (a capsule across the ray to the ball): refused.
  OwnBody body;
  const Eigen::Vector3d onRay = cm.pose.translation() + 0.3 * cm.pixelRay(b.image).normalized();
  body.parts.push_back({onRay - Eigen::Vector3d(0, 0.05, 0), onRay + Eigen::Vector3d(0, 0.05, 0), 0.03});
  EXPECT_FALSE(h.fix(body).run().get<BallPercept>().seen);
  // The same image without the ball: none.
  const CameraImage empty = test::syntheticImage(cm, {}, test::kNoPaint);
  const Upstream upEmpty(empty, cm);
  ModuleHarness h2 = harness<modules::BallPerceptor>();
  upEmpty.fixInto<CameraImage, DenoisedImage, ScanLineRegions, FieldColourReference, ObstaclesPercept, CameraMatrix,
                   VisionGeometry>(
      h2);
  EXPECT_FALSE(h2.fix(OwnBody{}).run().get<BallPercept>().seen);
}

TEST(LineSpotProvider, SpotsOnThePaintAndNoneInTheBall) {
  const CameraMatrix cm = standingCamera(0, 15);
  const CameraImage image = test::syntheticImage(cm, {}, segmentsPaint(kT));
  const Upstream up(image, cm);
  ModuleHarness h = harness<modules::LineSpotProvider>();
  up.fixInto<CameraImage, DenoisedImage, ScanLineRegions, FieldColourReference, ObstaclesPercept, CameraMatrix, VisionGeometry,
             BallPercept>(h);
  h.run();
  const LineSpots& spots = h.get<LineSpots>();
  ASSERT_GE(spots.spots.size(), 20u);
  int onPaint = 0;
  for (const auto& s : spots.spots)
    onPaint +=
        std::any_of(kT.begin(), kT.end(), [&](const Segment& seg) { return segmentDistance(s.ground, seg) < 0.06; });
  EXPECT_GE(onPaint, 0.95 * spots.spots.size());
  EXPECT_FALSE(spots.segments.empty());
  // A ball said to lie over the stem: no spot inside its disc.
  BallPercept ball;
  ball.seen = true;
  ball.position = {2.0, 0};
  ball.image = *cm.projectGround(ball.position);
  ball.radiusPx = 12;
  h.fix(ball).run();
  for (const auto& s : h.get<LineSpots>().spots) EXPECT_GT((s.image - ball.image).norm(), ball.radiusPx - 1);
}

TEST(CirclePerceptor, FindsTheCentreCircleAndMarksItsSpots) {
  const CameraMatrix cm = standingCamera(0, 18);
  const Eigen::Vector2d centre(1.7, 0.1);
  const CameraImage image = test::syntheticImage(
      cm, {}, [&](const Eigen::Vector2d& p) { return std::abs((p - centre).norm() - 0.75) <= 0.025; });
  const Upstream up(image, cm);
  ModuleHarness h = harness<modules::CirclePerceptor>();
  up.fixInto<LineSpots, CameraImage, FieldColourReference, ObstaclesPercept, CameraMatrix, VisionGeometry>(h);
  h.run();
  const CirclePercept& c = h.get<CirclePercept>();
  ASSERT_TRUE(c.circle.found);
  EXPECT_LT((c.circle.centre - centre).norm(), 0.05);
  const LineSpots& spots = up.pipeline.get<LineSpots>();
  ASSERT_EQ(c.spotsOnCircle.size(), spots.spots.size());
  EXPECT_GE(std::count(c.spotsOnCircle.begin(), c.spotsOnCircle.end(), 1), 0.8 * spots.spots.size());
  // Straight lines alone: no circle.
  const CameraImage straight = test::syntheticImage(cm, {}, segmentsPaint(kT));
  const Upstream upStraight(straight, cm);
  upStraight.fixInto<LineSpots, CameraImage, FieldColourReference, ObstaclesPercept, CameraMatrix, VisionGeometry>(h);
  EXPECT_FALSE(h.run().get<CirclePercept>().circle.found);
}

TEST(LinePerceptor, TheTwoLinesOfATAndNoneOnTheCircle) {
  const CameraMatrix cm = standingCamera(0, 15);
  const CameraImage image = test::syntheticImage(cm, {}, segmentsPaint(kT));
  const Upstream up(image, cm);
  ModuleHarness h = harness<modules::LinePerceptor>();
  up.fixInto<LineSpots, CirclePercept, CameraImage, FieldColourReference, ObstaclesPercept, CameraMatrix,
             VisionGeometry>(h);
  h.run();
  const FieldLines& lines = h.get<FieldLines>();
  ASSERT_EQ(lines.lines.size(), 2u);
  for (const Segment& truth : kT) {
    const Eigen::Vector2d u = (truth.second - truth.first).normalized();
    const bool found = std::any_of(lines.lines.begin(), lines.lines.end(), [&](const LinesPercept::Line& l) {
      const Eigen::Vector2d d = (l.to - l.from).normalized();
      return std::abs(u.x() * d.y() - u.y() * d.x()) < std::sin(2 * M_PI / 180) &&
             segmentDistance(l.from, truth) < 0.04 && segmentDistance(l.to, truth) < 0.04;
    });
    EXPECT_TRUE(found) << truth.first.transpose() << " - " << truth.second.transpose();
  }
  // Every spot said to lie on a circle: no line from them.
  CirclePercept all = up.pipeline.get<CirclePercept>();
  all.spotsOnCircle.assign(up.pipeline.get<LineSpots>().spots.size(), 1);
  h.fix(all).run();
  EXPECT_TRUE(h.get<FieldLines>().lines.empty());
}

LinesPercept::Line groundLine(const CameraMatrix& cm, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  LinesPercept::Line l;
  l.from = a, l.to = b;
  l.imageFrom = *cm.projectGround(a), l.imageTo = *cm.projectGround(b);
  return l;
}

TEST(IntersectionPerceptor, TheTOfThePaintAndAnLForAnL) {
  const CameraMatrix cm = standingCamera(0, 15);
  const CameraImage image = test::syntheticImage(cm, {}, segmentsPaint(kT));
  const Upstream up(image, cm);
  ModuleHarness h = harness<modules::IntersectionPerceptor>();
  up.fixInto<CameraMatrix, ObstaclesPercept, CameraImage, FieldColourReference>(h);
  // The lines given by hand: the stem and the whole crossbar.
  h.fix(FieldLines{{groundLine(cm, {1.5, 0}, {2.5, 0}), groundLine(cm, {1.5, -0.6}, {1.5, 0.6})}}).run();
  auto xs = h.get<IntersectionsPercept>().intersections;
  ASSERT_EQ(xs.size(), 1u);
  EXPECT_EQ(xs[0].type, LinesPercept::Intersection::Type::T);
  EXPECT_LT((xs[0].position - Eigen::Vector2d(1.5, 0)).norm(), 1e-6);
  // Only half the crossbar seen: the image shows the paint going on, so no L is claimed.
  h.fix(FieldLines{{groundLine(cm, {1.5, 0}, {2.5, 0}), groundLine(cm, {1.5, 0}, {1.5, 0.6})}}).run();
  EXPECT_TRUE(h.get<IntersectionsPercept>().intersections.empty());
}

TEST(PenaltyMarkPerceptor, TheCrossAndNotTheCentreMarkOnALine) {
  const CameraMatrix cm = standingCamera(0, 15);
  const Eigen::Vector2d cross(1.8, 0.2);
  const Paint crossPaint = [&](const Eigen::Vector2d& p) {
    const Eigen::Vector2d d = (p - cross).cwiseAbs();
    return (d.x() <= 0.05 && d.y() <= 0.025) || (d.y() <= 0.05 && d.x() <= 0.025);
  };
  const CameraImage image = test::syntheticImage(cm, {}, crossPaint);
  const Upstream up(image, cm);
  ModuleHarness h = harness<modules::PenaltyMarkPerceptor>();
  up.fixInto<CameraImage, ScanLineRegions, FieldColourReference, FieldLines, ObstaclesPercept, CameraMatrix,
             VisionGeometry, BallPercept>(h);
  h.run();
  const PenaltyMarkPercept& mark = h.get<PenaltyMarkPercept>();
  ASSERT_TRUE(mark.position.has_value());
  EXPECT_LT((*mark.position - cross).norm(), 0.05);
  EXPECT_LT((mark.image - *cm.projectGround(cross)).norm(), 4.0);
  // A line through it (the halfway line through the centre mark): no penalty mark.
  h.fix(FieldLines{{groundLine(cm, {cross.x(), -1.0}, {cross.x(), 1.0})}}).run();
  EXPECT_FALSE(h.get<PenaltyMarkPercept>().position.has_value());
}

TEST(GoalBoxSidePerceptor, AShortLineJoiningTwoLongLines) {
  auto line = [](Eigen::Vector2d a, Eigen::Vector2d b) {
    LinesPercept::Line l;
    l.imageFrom = a, l.imageTo = b;
    return l;
  };
  CameraImage image;
  image.width = 640, image.height = 480;
  ModuleHarness h = harness<modules::GoalBoxSidePerceptor>();
  h.fix(image);
  FieldLines lines{{line({100, 460}, {300, 120}), line({420, 460}, {360, 120}), line({242, 220}, {378, 222})}};
  h.fix(lines).run();
  const LinesPercept::GoalBoxSide& side = h.get<GoalBoxSidePercept>().side;
  ASSERT_TRUE(side.found);
  EXPECT_EQ(side.shortLine, 2);
  EXPECT_TRUE((side.longLine1 == 0 && side.longLine2 == 1) || (side.longLine1 == 1 && side.longLine2 == 0));
  lines.lines[2] = line({242, 220}, {320, 221});  // reaches only one long line
  EXPECT_FALSE(h.fix(lines).run().get<GoalBoxSidePercept>().side.found);
}

TEST(CameraPerceptsProvider, OneImagesPerceptsWithItsCameraTimeAndMatrix) {
  ModuleHarness h = harness<modules::CameraPerceptsProvider>();
  CameraImage image;
  image.camera = CameraId::Bottom;
  image.timestamp = 12.345;
  const CameraMatrix cm = standingCamera(10, 20, CameraId::Bottom);
  FieldBoundary boundary;
  boundary.valid = true;
  boundary.points = {{0, 10}, {320, 12}};
  ObstaclesPercept obstacles;
  obstacles.obstacles.resize(1);
  obstacles.obstacles[0].footRobot = {1, 2};
  BallPercept ball;
  ball.seen = true;
  ball.position = {0.4, -0.1};
  FieldLines lines{{groundLine(cm, {0.3, 0}, {0.6, 0})}};
  IntersectionsPercept xs;
  xs.intersections.resize(2);
  CirclePercept circle;
  circle.circle.found = true;
  circle.circle.centre = {3, 1};
  PenaltyMarkPercept mark;
  mark.position = Eigen::Vector2d(1.3, 0.2);
  mark.image = {100, 200};
  GoalBoxSidePercept side;
  side.side.found = true;
  side.side.shortLine = 0;
  h.fix(image).fix(cm).fix(boundary).fix(obstacles).fix(ball).fix(lines).fix(xs).fix(circle).fix(mark).fix(side).run();
  const CameraPercepts& p = h.get<CameraPercepts>();
  EXPECT_EQ(p.camera, CameraId::Bottom);
  EXPECT_EQ(p.timestamp, 12.345);
  EXPECT_TRUE(p.cameraMatrix.pose.isApprox(cm.pose));
  EXPECT_EQ(p.fieldBoundary.points.size(), 2u);
  ASSERT_EQ(p.obstacles.obstacles.size(), 1u);
  EXPECT_EQ(p.obstacles.obstacles[0].footRobot, Eigen::Vector2d(1, 2));
  EXPECT_TRUE(p.ball.seen);
  EXPECT_EQ(p.ball.position, ball.position);
  ASSERT_EQ(p.lines.size(), 1u);
  EXPECT_EQ(p.intersections.size(), 2u);
  EXPECT_TRUE(p.circle.found);
  ASSERT_TRUE(p.penaltyMark.has_value());
  EXPECT_EQ(*p.penaltyMark, Eigen::Vector2d(1.3, 0.2));
  EXPECT_EQ(p.penaltyMarkImage, Eigen::Vector2d(100, 200));
  EXPECT_TRUE(p.goalBoxSide.found);
  const LinesPercept old = p.linesPercept();
  EXPECT_EQ(old.lines.size(), 1u);
  EXPECT_EQ(old.intersections.size(), 2u);
  EXPECT_TRUE(old.circle.found && old.goalBoxSide.found && old.penaltyMark.has_value());
}

}  // namespace
}  // namespace nao
