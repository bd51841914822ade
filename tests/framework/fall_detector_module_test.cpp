// FallDetector alone: upright stays upright, a tilted IMU is a fall in the right direction,
// tipping is "falling", and its parameters come from the files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "controllers/modules/FallDetector.h"
#include "tests/support/ModuleHarness.h"

namespace nao {
namespace {

using testing::ModuleHarness;

SensorFrame frame(double t, double roll, double pitch, double pitchRate = 0, double feetKg = 4.5) {
  SensorFrame f;
  f.time = t;
  f.inertial.angle = {roll, pitch};
  f.inertial.gyroscope = {0, pitchRate, 0};
  f.fsr.weight.fill(feetKg / 8);
  return f;
}

TEST(FallDetectorModule, UprightIsNotAFall) {
  ModuleHarness h("FallDetector");
  for (int i = 0; i < 100; ++i) {
    h.fix(frame(i * 0.012, 0.05, -0.05)).run();
    ASSERT_FALSE(h.get<FallState>().falling);
    ASSERT_FALSE(h.get<FallState>().fallen);
  }
  EXPECT_EQ(h.get<FallState>().direction, FallDirection::None);
}

TEST(FallDetectorModule, TiltedImuIsAFallInItsDirection) {
  struct Case {
    double roll, pitch;
    FallDirection direction;
  };
  for (const Case c : {Case{0, 1.0, FallDirection::Front}, Case{0, -1.0, FallDirection::Back},
                       Case{1.0, 0, FallDirection::Right}, Case{-1.0, 0, FallDirection::Left}}) {
    ModuleHarness h = ModuleHarness::make<modules::FallDetector>();
    h.fix(frame(0, 0, 0)).run();
    h.fix(frame(0.5, c.roll, c.pitch)).run();
    const FallState& s = h.get<FallState>();
    EXPECT_TRUE(s.fallen) << c.roll << " " << c.pitch;
    EXPECT_EQ(s.direction, c.direction) << fallDirectionName(s.direction);
    EXPECT_DOUBLE_EQ(s.fallTime, 0.5);
  }
}

TEST(FallDetectorModule, TippingBeyondThirtyDegreesIsFalling) {
  ModuleHarness h("FallDetector");
  h.fix(frame(0, 0, 0.6, 1.5)).run();  // 34 deg, tipping at 1.5 rad/s, feet still loaded
  EXPECT_TRUE(h.get<FallState>().falling);
  EXPECT_FALSE(h.get<FallState>().fallen);
  EXPECT_EQ(h.get<FallState>().direction, FallDirection::Front);
  h.fix(frame(0.012, 0, 0.6, 0)).run();  // held there, not tipping further
  EXPECT_FALSE(h.get<FallState>().falling);
}

TEST(FallDetectorModule, ParametersFromFileAndOverlay) {
  const auto dir = std::filesystem::temp_directory_path() / "nao_fall_module_test";
  std::filesystem::create_directories(dir / "parameters");
  std::filesystem::create_directories(dir / "robots" / "head1");
  std::ofstream(dir / "parameters" / "FallDetector.json") << R"({"fallenAngle": 1.2})";
  std::ofstream(dir / "robots" / "head1" / "FallDetector.json") << R"({"fallenAngle": 0.9})";
  ModuleHarness lenient("FallDetector", ModuleContext{dir.string(), "", {}});
  lenient.fix(frame(0, 0, 1.0)).run();  // 57 deg with the feet loaded: not down for 1.2 rad
  EXPECT_FALSE(lenient.get<FallState>().fallen);
  ModuleHarness robot("FallDetector", ModuleContext{dir.string(), "head1", {}});
  robot.fix(frame(0, 0, 1.0)).run();
  EXPECT_TRUE(robot.get<FallState>().fallen);
  std::ofstream(dir / "parameters" / "FallDetector.json") << R"({"fallenAngle": "steep"})";
  try {
    ModuleHarness bad("FallDetector", ModuleContext{dir.string(), "", {}});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "parameters" / "FallDetector.json").string() + ": fallenAngle: must be a number");
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace nao
