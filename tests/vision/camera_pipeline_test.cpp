// The camera pipeline (perception/vision/CameraPipeline.h): its percepts equal those of the
// hand-ordered vision it replaced (the same stages called in the old order, written out below
// as it stood in runVision before the modules) on synthetic and simulated images of both
// cameras; the order follows from the declarations; a provider can be swapped; every module
// is timed; bad use is refused.
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>

#include "controllers/StandController.h"
#include "perception/vision/BallClassifier.h"
#include "perception/vision/BallDetector.h"
#include "perception/vision/CameraPipeline.h"
#include "perception/vision/CircleDetector.h"
#include "perception/vision/FieldBoundaryDetector.h"
#include "perception/vision/GoalBoxDetector.h"
#include "perception/vision/IntersectionDetector.h"
#include "perception/vision/LineDetector.h"
#include "perception/vision/ObstacleDetector.h"
#include "perception/vision/PenaltyMarkDetector.h"
#include "perception/vision/ScanGrid.h"
#include "perception/vision/ScanLineRegionizer.h"
#include "perception/vision/VisionPipeline.h"
#include "robot/Error.h"
#include "robot/ModuleRegistry.h"
#include "robot/Paths.h"
#include "sim/CameraRenderer.h"
#include "sim/Lighting.h"
#include "sim/World.h"
#include "tests/support/StandingCamera.h"
#include "tests/support/SyntheticScene.h"

namespace nao {

// A stand-in ball percept (as an oracle from the simulator's truth would be): swapped in
// through CameraPipelineConfig::providers.
namespace modules {
class FixedBallPerceptForTest
    : public Module<FixedBallPerceptForTest, Requires<CameraImage>, Provides<BallPercept>, Cadence::Cognition> {
 public:
  explicit FixedBallPerceptForTest(const ModuleContext&) {}

 private:
  void update() override {
    BallPercept& b = out<BallPercept>();
    b.seen = true;
    b.position = {1.25, -0.5};
    b.image = {in<CameraImage>().width / 2.0, 400};
  }
};
NAO_REGISTER_MODULE(FixedBallPerceptForTest);
}  // namespace modules

namespace {

constexpr double kDeg = M_PI / 180;

// The vision as runVision ran it before the modules (commit e348c0b), stage by stage.
VisionResult handOrderedVision(const CameraImage& image, const CameraMatrix& cm, const VisionGeometry& geometry) {
  VisionResult r;
  const ScanGrid grid = makeScanGrid(cm, image.width, image.height, geometry.lineWidth);
  const ScanLineRegions all = computeScanLineRegions(image, grid, nullptr);
  r.boundary = detectFieldBoundary(image, all, cm);
  r.regions = cutAtBoundary(all, r.boundary);
  r.obstacles = detectObstacles(image, r.regions, r.boundary, cm);
  vision::BallParams ballParams;
  ballParams.radius = geometry.ballRadius;
  ballParams.classifier = &vision::defaultBallClassifier();
  const vision::FieldReference field = vision::FieldReference::from(r.regions);
  r.ball = vision::detectBall(image, r.regions, field, r.obstacles, cm, ballParams);
  vision::LineParams lineParams;
  lineParams.lineWidth = geometry.lineWidth;
  lineParams.circleRadius = geometry.circleRadius;
  const vision::LineCandidates candidates =
      vision::findLineCandidates(image, r.regions, field, r.obstacles, cm, lineParams, &r.ball);
  vision::CircleParams circleParams;
  circleParams.radius = geometry.circleRadius;
  circleParams.lineWidth = geometry.lineWidth;
  std::vector<char> onCircle;
  r.lines.circle = vision::detectCircle(candidates, image, field, r.obstacles, cm, circleParams, &onCircle);
  r.lines.lines = vision::fitLines(candidates, onCircle, image, field, r.obstacles, cm, lineParams);
  r.lines.intersections = vision::detectIntersections(r.lines.lines, cm, r.obstacles, {}, &image, &field);
  vision::PenaltyMarkParams penaltyParams;
  penaltyParams.size = geometry.penaltyCrossSize;
  r.lines.penaltyMark = vision::detectPenaltyMark(image, r.regions, field, r.lines.lines, r.obstacles, cm,
                                                  penaltyParams, &r.penaltyMarkImage, &r.ball);
  r.lines.goalBoxSide = vision::detectGoalBoxSide(r.lines.lines, image.width, image.height, vision::GoalBoxParams{});
  return r;
}

// Exact equality: the same functions on the same inputs give the same bits.
void expectSame(const VisionResult& a, const CameraPercepts& p, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(a.lines.lines.size(), p.lines.size());
  for (std::size_t i = 0; i < p.lines.size(); ++i) {
    EXPECT_EQ(a.lines.lines[i].from, p.lines[i].from);
    EXPECT_EQ(a.lines.lines[i].to, p.lines[i].to);
    EXPECT_EQ(a.lines.lines[i].imageFrom, p.lines[i].imageFrom);
    EXPECT_EQ(a.lines.lines[i].imageTo, p.lines[i].imageTo);
    EXPECT_EQ(a.lines.lines[i].spots.size(), p.lines[i].spots.size());
  }
  ASSERT_EQ(a.lines.intersections.size(), p.intersections.size());
  for (std::size_t i = 0; i < p.intersections.size(); ++i) {
    EXPECT_EQ(a.lines.intersections[i].type, p.intersections[i].type);
    EXPECT_EQ(a.lines.intersections[i].position, p.intersections[i].position);
    EXPECT_EQ(a.lines.intersections[i].line1, p.intersections[i].line1);
    EXPECT_EQ(a.lines.intersections[i].line2, p.intersections[i].line2);
  }
  EXPECT_EQ(a.lines.circle.found, p.circle.found);
  EXPECT_EQ(a.lines.circle.centre, p.circle.centre);
  EXPECT_EQ(a.lines.penaltyMark.has_value(), p.penaltyMark.has_value());
  if (a.lines.penaltyMark && p.penaltyMark) {
    EXPECT_EQ(*a.lines.penaltyMark, *p.penaltyMark);
  }
  EXPECT_EQ(a.penaltyMarkImage, p.penaltyMarkImage);
  EXPECT_EQ(a.lines.goalBoxSide.found, p.goalBoxSide.found);
  EXPECT_EQ(a.lines.goalBoxSide.shortLine, p.goalBoxSide.shortLine);
  EXPECT_EQ(a.lines.goalBoxSide.longLine1, p.goalBoxSide.longLine1);
  EXPECT_EQ(a.lines.goalBoxSide.longLine2, p.goalBoxSide.longLine2);
  EXPECT_EQ(a.ball.seen, p.ball.seen);
  EXPECT_EQ(a.ball.position, p.ball.position);
  EXPECT_EQ(a.ball.image, p.ball.image);
  EXPECT_EQ(a.ball.radiusPx, p.ball.radiusPx);
  EXPECT_EQ(a.ball.covariance, p.ball.covariance);
  EXPECT_EQ(a.ball.confidence, p.ball.confidence);
  ASSERT_EQ(a.obstacles.obstacles.size(), p.obstacles.obstacles.size());
  for (std::size_t i = 0; i < p.obstacles.obstacles.size(); ++i) {
    const auto &x = a.obstacles.obstacles[i], &y = p.obstacles.obstacles[i];
    EXPECT_TRUE(x.left == y.left && x.right == y.right && x.top == y.top && x.bottom == y.bottom);
    EXPECT_EQ(x.footRobot, y.footRobot);
  }
  EXPECT_EQ(a.boundary.valid, p.fieldBoundary.valid);
  EXPECT_EQ(a.boundary.points, p.fieldBoundary.points);
}

void expectSameRegions(const ScanLineRegions& a, const ScanLineRegions& b) {
  ASSERT_EQ(a.vertical.size(), b.vertical.size());
  ASSERT_EQ(a.horizontal.size(), b.horizontal.size());
  for (std::size_t i = 0; i < a.vertical.size(); ++i) {
    ASSERT_EQ(a.vertical[i].regions.size(), b.vertical[i].regions.size());
    for (std::size_t k = 0; k < a.vertical[i].regions.size(); ++k) {
      EXPECT_EQ(a.vertical[i].regions[k].from, b.vertical[i].regions[k].from);
      EXPECT_EQ(a.vertical[i].regions[k].to, b.vertical[i].regions[k].to);
      EXPECT_EQ(a.vertical[i].regions[k].cls, b.vertical[i].regions[k].cls);
    }
  }
  EXPECT_EQ(a.fieldColour.hueMin, b.fieldColour.hueMin);
  EXPECT_EQ(a.fieldColour.whiteYMin, b.fieldColour.whiteYMin);
}

struct Frame {
  std::string name;
  CameraImage image;
  CameraMatrix cm;
};

std::vector<Frame> syntheticFrames() {
  using test::standingCamera;
  std::vector<Frame> frames;
  const auto segment = [](Eigen::Vector2d a, Eigen::Vector2d b) {
    return [a, b](const Eigen::Vector2d& p) {
      const Eigen::Vector2d d = b - a;
      const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
      return (a + t * d - p).norm() <= 0.025;
    };
  };
  const auto t1 = segment({1.5, 0}, {2.5, 0}), t2 = segment({1.5, -0.6}, {1.5, 0.6});
  const CameraMatrix cm15 = standingCamera(0, 15), cm18 = standingCamera(0, 18);
  frames.push_back(
      {"T", test::syntheticImage(cm15, {}, [&](const Eigen::Vector2d& p) { return t1(p) || t2(p); }), cm15});
  const Eigen::Vector2d centre(1.7, 0.1);
  frames.push_back(
      {"circle",
       test::syntheticImage(cm18, {},
                            [&](const Eigen::Vector2d& p) { return std::abs((p - centre).norm() - 0.75) <= 0.025; }),
       cm18});
  const Eigen::Vector2d cross(1.8, 0.2);
  frames.push_back({"cross",
                    test::syntheticImage(cm15, {},
                                         [&](const Eigen::Vector2d& p) {
                                           const Eigen::Vector2d d = (p - cross).cwiseAbs();
                                           return (d.x() <= 0.05 && d.y() <= 0.025) ||
                                                  (d.y() <= 0.05 && d.x() <= 0.025);
                                         }),
                    cm15});
  frames.push_back({"ball on a line",
                    test::syntheticImage(
                        cm15, {{Eigen::Vector3d(1.5, 0.3, 0.05), 0.05, test::soccerBall(Eigen::Matrix3d::Identity())}},
                        [&](const Eigen::Vector2d& p) { return t2(p); }),
                    cm15});
  return frames;
}

// Simulated images of both cameras from random poses on the field, under several lightings.
std::vector<Frame> simulatedFrames(int n) {
  sim::SceneSpec spec;
  spec.field = FieldDimensions::load(dataPath("config/field_dimensions.json"));
  spec.robots = {Eigen::Vector3d(0, 0, 0)};
  spec.balls = {Eigen::Vector3d(1, 0, 0.05)};
  sim::World world(spec, 5);
  sim::CameraRenderer renderer(world.model());
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> uni(0, 1);
  const char* presets[] = {"default", "dark", "warm", "shadows"};
  std::vector<Frame> frames;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d pose((uni(rng) - 0.5) * 8, (uni(rng) - 0.5) * 5, (uni(rng) - 0.5) * 2 * M_PI);
    JointArray posture = StandController::standPosture();
    posture[HeadYaw] = (uni(rng) - 0.5) * 140 * kDeg;
    posture[HeadPitch] = (uni(rng) * 30 - 8) * kDeg;
    world.placeRobot(0, pose, posture);
    const double bearing = pose.z() + posture[HeadYaw] + (uni(rng) - 0.5) * 50 * kDeg, dist = 0.4 + 3 * uni(rng);
    world.placeBall(0, Eigen::Vector3d(pose.x() + dist * std::cos(bearing), pose.y() + dist * std::sin(bearing), 0.05));
    const SensorFrame s = world.sensors(0);
    const sim::Lighting lighting = sim::Lighting::parse(presets[i % 4], dataPath("config/lighting.json"));
    for (CameraId camera : {CameraId::Top, CameraId::Bottom}) {
      const sim::CameraResolution res = world.cameraResolution(camera);
      const CameraMatrix cm =
          computeCameraMatrix(s.joints.position, s.inertial.angle, camera, CameraCalibration{},
                              CameraIntrinsics::fromFovY(res.width, res.height, world.cameraFovY()));
      frames.push_back({std::string("sim ") + std::to_string(i) + " " + cameraName(camera) + " " + presets[i % 4],
                        renderer.renderImage(world.model(), world.data(), world.cameraIndex(0, camera), res.width,
                                             res.height, lighting, camera, 0, rng, ExposureWeights{}),
                        cm});
    }
  }
  return frames;
}

TEST(CameraPipeline, SamePerceptsAsTheHandOrderedVision) {
  std::vector<Frame> frames = syntheticFrames();
  for (Frame& f : simulatedFrames(12)) frames.push_back(std::move(f));
  CameraPipeline pipelines[] = {CameraPipeline(CameraId::Top, VisionGeometry{}),
                                CameraPipeline(CameraId::Bottom, VisionGeometry{})};
  int lines = 0, balls = 0, intersections = 0;
  for (const Frame& f : frames) {
    CameraPipeline& p = pipelines[static_cast<int>(f.image.camera)];
    const CameraPercepts& percepts = p.process(f.image, f.cm);
    const VisionResult old = handOrderedVision(f.image, f.cm, VisionGeometry{});
    expectSame(old, percepts, f.name);
    expectSameRegions(old.regions, p.get<ScanLineRegions>());
    // runVision, the wrapper, too.
    expectSame(runVision(f.image, f.cm), percepts, f.name + " (runVision)");
    EXPECT_EQ(percepts.camera, f.image.camera);
    EXPECT_EQ(percepts.timestamp, f.image.timestamp);
    EXPECT_TRUE(percepts.cameraMatrix.pose.isApprox(f.cm.pose));
    lines += static_cast<int>(percepts.lines.size());
    intersections += static_cast<int>(percepts.intersections.size());
    balls += percepts.ball.seen;
  }
  // The images hold something to compare.
  EXPECT_GE(lines, 15);
  EXPECT_GE(intersections, 3);
  EXPECT_GE(balls, 5);
}

TEST(CameraPipeline, FieldGeometryFromTheFieldFile) {
  FieldDimensions reduced = FieldDimensions::load(dataPath("config/field_dimensions.json"));
  reduced.lineWidth = 0.08;
  const CameraPipeline p(CameraId::Top, reduced);
  EXPECT_EQ(p.geometry().lineWidth, 0.08);
  EXPECT_EQ(p.geometry().circleRadius, VisionGeometry::from(reduced).circleRadius);
}

TEST(CameraPipeline, OrderFromTheDeclarationsAndEveryModuleTimed) {
  CameraPipeline p(CameraId::Top, VisionGeometry{});
  const std::vector<std::string> order = p.order();
  ASSERT_EQ(order.size(), 15u);
  const auto at = [&](const std::string& name) { return std::find(order.begin(), order.end(), name) - order.begin(); };
  EXPECT_LT(at("ScanGridProvider"), at("ScanLineRegionProvider"));
  EXPECT_LT(at("ImageDenoiser"), at("ScanLineRegionProvider"));
  EXPECT_LT(at("ImageDenoiser"), at("BallPerceptor"));
  EXPECT_EQ(order.back(), "CameraPerceptsProvider");
  EXPECT_LT(at("FieldBoundaryProvider"), at("ScanLineRegionCutter"));
  EXPECT_LT(at("BallPerceptor"), at("LineSpotProvider"));
  EXPECT_LT(at("CirclePerceptor"), at("LinePerceptor"));
  EXPECT_LT(at("LinePerceptor"), at("IntersectionPerceptor"));
  EXPECT_LT(at("LinePerceptor"), at("PenaltyMarkPerceptor"));
  const Frame f = syntheticFrames().front();
  p.process(f.image, f.cm);
  ASSERT_EQ(p.moduleMs().size(), order.size());
  double sum = 0;
  for (std::size_t i = 0; i < order.size(); ++i) {
    EXPECT_EQ(p.moduleMs()[i].module, order[i]);
    EXPECT_GE(p.moduleMs()[i].ms, 0);
    sum += p.moduleMs()[i].ms;
  }
  EXPECT_GE(p.totalMs(), sum);
  const VisionResult r = p.visionResult();
  EXPECT_EQ(r.stageMs.size(), order.size() + 1);
  EXPECT_EQ(r.stageMs.at("total"), p.totalMs());
}

TEST(CameraPipeline, AProviderSwappedThroughTheConfiguration) {
  CameraPipelineConfig config;
  config.providers = {{"BallPercept", "FixedBallPerceptForTest"}};
  CameraPipeline p(CameraId::Top, VisionGeometry{}, config);
  const auto order = p.order();
  EXPECT_EQ(std::count(order.begin(), order.end(), "BallPerceptor"), 0);
  EXPECT_EQ(std::count(order.begin(), order.end(), "FixedBallPerceptForTest"), 1);
  const Frame f = syntheticFrames().front();  // no ball in it
  const CameraPercepts& percepts = p.process(f.image, f.cm);
  EXPECT_TRUE(percepts.ball.seen);
  EXPECT_EQ(percepts.ball.position, Eigen::Vector2d(1.25, -0.5));
  // The lines are still the real modules'.
  EXPECT_EQ(percepts.lines.size(), 2u);
  // A module that does not provide the representation is refused, naming the key.
  config.providers = {{"BallPercept", "LinePerceptor"}};
  try {
    CameraPipeline bad(CameraId::Top, VisionGeometry{}, config);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(
        std::string(e.what()),
        "CameraPipelineConfig.providers: providers.BallPercept: module LinePerceptor does not provide BallPercept");
  }
}

TEST(CameraPipeline, AnInvalidImageSeesNothingAndTheOtherCameraIsRefused) {
  CameraPipeline p(CameraId::Bottom, VisionGeometry{});
  CameraImage empty;
  empty.camera = CameraId::Bottom;
  empty.timestamp = 3.5;
  const CameraPercepts& percepts = p.process(empty, test::standingCamera(0, 0, CameraId::Bottom));
  EXPECT_EQ(percepts.camera, CameraId::Bottom);
  EXPECT_EQ(percepts.timestamp, 3.5);
  EXPECT_FALSE(percepts.ball.seen);
  EXPECT_TRUE(percepts.lines.empty());
  EXPECT_TRUE(p.moduleMs().empty());
  EXPECT_TRUE(p.visionResult().stageMs.empty());
  EXPECT_FALSE(runVision(empty, test::standingCamera(0, 0)).ball.seen);
  const Frame top = syntheticFrames().front();
  try {
    p.process(top.image, top.cm);
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "camera pipeline: an image of the top camera given to the bottom camera's pipeline");
  }
}

// config/camera_modules.json: every chosen module runs once per image, and docs/architecture.md
// lists each choice.
TEST(CameraPipeline, CommittedConfigurationAndItsDocumentation) {
  const ProviderMap providers = loadProviders(CameraPipeline::defaultProvidersFile());
  const std::vector<ModuleInfo> all = registeredModules();
  std::ifstream in(dataPath("docs/architecture.md"));
  std::stringstream doc;
  doc << in.rdbuf();
  for (const auto& [rep, module] : providers) {
    const auto it = std::find_if(all.begin(), all.end(), [&name = module](const ModuleInfo& m) { return m.name == name; });
    ASSERT_NE(it, all.end()) << module;
    EXPECT_EQ(it->cadence, Cadence::Cognition) << module;
    const std::string row = "| `" + rep + "` | `" + module + "` | cognition |";
    EXPECT_NE(doc.str().find(row), std::string::npos) << "docs/architecture.md lacks the row " << row;
  }
  EXPECT_EQ(providers.at("CameraPercepts"), "CameraPerceptsProvider");
}

}  // namespace
}  // namespace nao
