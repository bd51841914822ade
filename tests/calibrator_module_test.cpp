// The Calibrator module (cognition) on rendered views of the goal box: a robot with injected
// camera offsets is placed at each planned view (a test fixture may place it; the challenge's
// robot walks there), the module takes the samples from the images with the joints and IMU of
// the FrameHistory, solves, applies and verifies; the estimate is judged against the offsets
// the simulator injected. And what it refuses: a moving head, too few samples, stale requests.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "controllers/StandController.h"
#include "controllers/modules/Calibrator.h"
#include "perception/FieldDimensions.h"
#include "perception/calibration/CalibrationViews.h"
#include "robot/Paths.h"
#include "sim/CameraRenderer.h"
#include "sim/Lighting.h"
#include "sim/World.h"
#include "tests/support/ModuleHarness.h"

namespace nao {
namespace {

using testing::ModuleHarness;
namespace cal = calibration;
constexpr double kDeg = M_PI / 180;

FieldDimensions field() { return FieldDimensions::load(dataPath("config/field_dimensions.json")); }

ModuleContext fieldContext() {
  ModuleContext c;
  c.params["FieldDimensions"] = field();
  return c;
}

// A simulated robot with injected offsets, placed at views and photographed when still.
struct ViewFixture {
  FieldDimensions f = field();
  sim::World world;
  sim::CameraRenderer renderer;
  sim::Lighting lighting = sim::Lighting::parse("default", dataPath("config/lighting.json"));
  std::mt19937_64 rng{7};
  FrameHistory history;
  int side = -1;
  explicit ViewFixture(const CameraCalibration& offsets)
      : world(spec(), 11), renderer(world.model()) {
    world.setMiscalibration(0, offsets);
  }
  sim::SceneSpec spec() const {
    sim::SceneSpec s;
    s.field = field();
    return s;
  }
  std::vector<cal::CalibrationView> views(const cal::ViewPlanOptions& o = {}) const {
    const cal::GoalBoxSide box = cal::ownGoalBoxSide(f, side);
    const Eigen::Vector3d pose = cal::calibrationPosition(box, o);
    return cal::planViews(box, pose.head<2>(), StandController::standPosture(), o);
  }
  // Places the robot for the view and steps until it is still; the FrameHistory holds the last
  // 0.5 s of cycles (moving: the head turns during them).
  CameraImage shoot(const cal::CalibrationView& v, bool moving = false) {
    JointArray posture = StandController::standPosture();
    posture[HeadYaw] = v.headYaw;
    posture[HeadPitch] = v.headPitch;
    world.placeRobot(0, v.robotPose, posture);
    history.entries.clear();
    for (int c = 0; c < 80; ++c) {
      if (moving && c >= 50) {
        JointRequest r;
        r.position = posture;
        r.position[HeadYaw] = v.headYaw + 0.004 * (c - 49);
        r.stiffness.fill(1.0);
        world.setJointRequest(0, r);
      }
      world.stepCycle();
      const SensorFrame s = world.sensors(0);
      FrameHistory::Entry e;
      e.time = s.time;
      e.joints = s.joints.position;
      e.imuAngle = s.inertial.angle;
      history.entries.push_back(e);
      while (history.entries.size() > 42) history.entries.pop_front();
    }
    const sim::CameraResolution res = world.cameraResolution(v.camera);
    return renderer.renderImage(world.model(), world.data(), world.cameraIndex(0, v.camera), res.width, res.height,
                                lighting, v.camera, world.time(), rng, ExposureWeights{});
  }
};

struct CalibratorFixture {
  ModuleHarness h{"Calibrator", fieldContext()};
  ChallengeMode mode;
  CalibrationRequest request;
  CalibratorFixture() { mode.modeId = 1; }
  const CalibrationStatus& run(const CameraImage& image, const FrameHistory& history) {
    CurrentImage current;
    current.image = image;
    h.fix(current).fix(history).fix(CameraCalibration{}).fix(request).fix(mode).run();
    return h.get<CalibrationStatus>();
  }
};

TEST(CalibratorModule, SolvesAppliesAndVerifiesTheInjectedOffsets) {
  const CameraCalibration truth = CameraCalibration::fromArray(
      {1.5 * kDeg, -1.0 * kDeg, -2.0 * kDeg, 2.5 * kDeg, 1.0 * kDeg, -1.5 * kDeg});
  ViewFixture views(truth);
  CalibratorFixture c;
  int viewId = 0;
  for (const cal::CalibrationView& v : views.views()) {
    const CameraImage image = views.shoot(v);
    c.request = {CalibrationRequest::Action::Collect, ++viewId, v.camera, 0};
    const CalibrationStatus& s = c.run(image, views.history);
    EXPECT_EQ(s.last.viewId, viewId);
    EXPECT_TRUE(s.last.accepted) << cameraName(v.camera) << " at " << v.headYaw / kDeg << " deg: " << s.last.reason;
    // The same view again, or another camera's image: no second sample.
    const int samples = s.samples[0] + s.samples[1];
    c.run(image, views.history);
    EXPECT_EQ(c.h.get<CalibrationStatus>().samples[0] + c.h.get<CalibrationStatus>().samples[1], samples);
  }
  const CalibrationStatus& s0 = c.h.get<CalibrationStatus>();
  EXPECT_GE(s0.samples[0], 4);
  EXPECT_GE(s0.samples[1], 4);
  const CameraImage last = views.shoot(views.views()[2]);
  c.request = {CalibrationRequest::Action::Solve, viewId, CameraId::Top, 1};
  const CalibrationStatus& solved = c.run(last, views.history);
  ASSERT_EQ(solved.solutionId, 1);
  EXPECT_TRUE(solved.accepted) << solved.reason;
  const auto est = solved.offsets.toArray(), tru = truth.toArray();
  for (int k = 0; k < 6; ++k) {
    EXPECT_NEAR(est[k] / kDeg, tru[k] / kDeg, 0.05) << k;
    std::printf("offset %d: true %+.3f deg, estimated %+.3f deg\n", k, tru[k] / kDeg, est[k] / kDeg);
  }
  std::printf("samples %d top + %d bottom, rms angle %.3f deg\n", solved.samples[0], solved.samples[1], solved.rmsAngleDeg);
  EXPECT_EQ(solved.appliedId, 0) << "applied before it was asked";
  c.request = {CalibrationRequest::Action::Apply, viewId, CameraId::Top, 1};
  const CalibrationStatus& applied = c.run(last, views.history);
  EXPECT_EQ(applied.appliedId, 1);
  EXPECT_EQ(applied.applied.toArray(), solved.offsets.toArray());
  c.run(last, views.history);
  EXPECT_EQ(c.h.get<CalibrationStatus>().appliedId, 1) << "applied twice";
  // A new view with the applied offsets: the goal box's corners are right angles again.
  c.request = {CalibrationRequest::Action::Verify, ++viewId, CameraId::Top, 1};
  const CalibrationStatus& verified = c.run(views.shoot(views.views()[2]), views.history);
  EXPECT_GE(verified.verifyAngleDeg, 0);
  EXPECT_LT(verified.verifyAngleDeg, 0.1);
  std::printf("verified: %.3f deg\n", verified.verifyAngleDeg);
  // A new challenge start forgets the samples, not the offsets in use.
  c.mode.modeId = 2;
  c.request = {};
  const CalibrationStatus& fresh = c.run(last, views.history);
  EXPECT_EQ(fresh.samples[0] + fresh.samples[1], 0);
  EXPECT_EQ(fresh.appliedId, 1);
  EXPECT_EQ(fresh.solutionId, 1);
}

TEST(CalibratorModule, RefusesAMovingHeadAndAnUnderdeterminedSolve) {
  ViewFixture views(CameraCalibration::fromArray({0, 1 * kDeg, 0, -1 * kDeg, 0, 0}));
  CalibratorFixture c;
  const auto plan = views.views();
  c.request = {CalibrationRequest::Action::Collect, 1, plan[2].camera, 0};
  const CalibrationStatus& moving = c.run(views.shoot(plan[2], true), views.history);
  EXPECT_EQ(moving.last.reason, "head moving");
  EXPECT_EQ(moving.last.viewId, -1) << "a moving head's image used up the view";
  const CalibrationStatus& still = c.run(views.shoot(plan[2]), views.history);
  EXPECT_EQ(still.last.viewId, 1);
  EXPECT_TRUE(still.last.accepted) << still.last.reason;
  // One sample: the solve refuses, with the reason.
  c.request = {CalibrationRequest::Action::Solve, 1, plan[2].camera, 1};
  const CalibrationStatus& solved = c.run(views.shoot(plan[2]), views.history);
  EXPECT_EQ(solved.solutionId, 1);
  EXPECT_FALSE(solved.accepted);
  EXPECT_NE(solved.reason.find("sample"), std::string::npos) << solved.reason;
  c.request = {CalibrationRequest::Action::Apply, 1, plan[2].camera, 1};
  EXPECT_EQ(c.run(views.shoot(plan[2]), views.history).appliedId, 0) << "a refused solution was applied";
}

}  // namespace
}  // namespace nao
