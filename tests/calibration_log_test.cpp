// The calibration log (perception/calibration/CalibrationLog.h, controllers/CalibrationLogging.h):
// a log survives writing and reading bit for bit; every cut of it, and every corrupted field,
// is refused with the source and the record named; the recorder keeps exactly the images the
// Calibrator judged, with the joints of the exposure. (calibration_sim_test: a recorded phase 1
// replayed through the Calibrator gives the live solution.)
#include <gtest/gtest.h>

#include <random>

#include "controllers/CalibrationLogging.h"
#include "perception/calibration/CalibrationLog.h"
#include "representations/infrastructure/ChallengeMode.h"
#include "representations/infrastructure/FrameHistory.h"
#include "robot/Error.h"

namespace nao {
namespace {

using calibration::CalibrationLog;
using calibration::CalibrationLogRecord;

CalibrationLogRecord record(int view, CameraId camera, int width, int height, std::uint32_t seed) {
  CalibrationLogRecord r;
  r.viewId = view;
  r.image.camera = camera;
  r.image.width = width;
  r.image.height = height;
  r.image.timestamp = 10.25 + view;
  std::mt19937 rng(seed);
  r.image.yuyv.resize(static_cast<std::size_t>(width) * height * 2);
  for (auto& b : r.image.yuyv) b = static_cast<std::uint8_t>(rng());
  for (int j = 0; j < NumJoints; ++j) r.joints[j] = 0.01 * j - 0.1 * view;
  r.imuAngle = Eigen::Vector2d(0.003 * view, -0.02);
  r.accepted = view % 2 == 0;
  r.reason = r.accepted ? "" : "goal box not found: no short line joining two long lines";
  return r;
}

CalibrationLog smallLog() {
  CalibrationLog log;
  log.headId = "head-a";
  log.backend = "nao";
  log.records = {record(1, CameraId::Top, 8, 4, 1), record(2, CameraId::Bottom, 4, 2, 2), record(3, CameraId::Top, 6, 2, 3)};
  return log;
}

void expectSame(const CalibrationLog& a, const CalibrationLog& b) {
  EXPECT_EQ(a.headId, b.headId);
  EXPECT_EQ(a.backend, b.backend);
  ASSERT_EQ(a.records.size(), b.records.size());
  for (std::size_t k = 0; k < a.records.size(); ++k) {
    const CalibrationLogRecord &x = a.records[k], &y = b.records[k];
    EXPECT_EQ(x.viewId, y.viewId);
    EXPECT_EQ(x.image.camera, y.image.camera);
    EXPECT_EQ(x.image.timestamp, y.image.timestamp);
    EXPECT_EQ(x.image.width, y.image.width);
    EXPECT_EQ(x.image.height, y.image.height);
    EXPECT_EQ(x.image.yuyv, y.image.yuyv);
    EXPECT_EQ(x.joints, y.joints);
    EXPECT_EQ(x.imuAngle, y.imuAngle);
    EXPECT_EQ(x.accepted, y.accepted);
    EXPECT_EQ(x.reason, y.reason);
  }
}

std::string errorOf(const std::string& bytes) {
  try {
    calibration::parseCalibrationLog(bytes, "log.bin");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(CalibrationLog, WrittenAndReadBitForBit) {
  const CalibrationLog log = smallLog();
  expectSame(calibration::parseCalibrationLog(calibration::serializeCalibrationLog(log), "log.bin"), log);
  CalibrationLog empty;
  empty.headId = "h";
  empty.backend = "sim";
  EXPECT_TRUE(calibration::parseCalibrationLog(calibration::serializeCalibrationLog(empty), "x").records.empty());
}

TEST(CalibrationLog, EveryCutIsRefusedNamingTheSourceAndTheRecord) {
  const std::string bytes = calibration::serializeCalibrationLog(smallLog());
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    const std::string e = errorOf(bytes.substr(0, n));
    ASSERT_FALSE(e.empty()) << "a log cut after " << n << " bytes was read";
    EXPECT_EQ(e.rfind("log.bin: ", 0), 0u) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    EXPECT_TRUE(e.find(": start: ") != std::string::npos || e.find(": header: ") != std::string::npos ||
                e.find(": record ") != std::string::npos)
        << e;
  }
  // Cut exactly after a whole record: the missing end marker says so.
  CalibrationLog two = smallLog();
  two.records.pop_back();
  const std::string prefix = calibration::serializeCalibrationLog(two);
  const std::string cut = prefix.substr(0, prefix.rfind("{\"end\"") - 4);  // without the end marker's chunk
  EXPECT_NE(errorOf(cut).find("record 3: truncated: the log ends after record 2 without its end marker"), std::string::npos)
      << errorOf(cut);
  EXPECT_NE(errorOf(bytes + "x").find("end marker: bytes after it"), std::string::npos);
}

TEST(CalibrationLog, CorruptFieldsAreNamed) {
  const std::string good = calibration::serializeCalibrationLog(smallLog());
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    const std::size_t at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    // Same length, so the chunk's length prefix stays right.
    EXPECT_EQ(from.size(), to.size());
    return s.replace(at, from.size(), to);
  };
  EXPECT_NE(errorOf("NOTALOG").find("log.bin: start: not a calibration log"), std::string::npos);
  EXPECT_NE(errorOf(replaced("\"format\":1", "\"format\":7")).find("header: format 7"), std::string::npos);
  EXPECT_NE(errorOf(replaced("\"camera\":\"top\"", "\"camera\":\"tip\"")).find("record 1: 'camera' is 'tip'"), std::string::npos);
  EXPECT_NE(errorOf(replaced("\"width\":8", "\"width\":7")).find("record 1: image size 7x4"), std::string::npos);
  EXPECT_NE(errorOf(replaced("\"width\":8", "\"width\":6")).find("record 1: the image holds 64 bytes"), std::string::npos);
  EXPECT_NE(errorOf(replaced("\"view\":2", "\"vie_\":2")).find("record 2: 'view' missing"), std::string::npos);
  EXPECT_NE(errorOf(replaced("\"accepted\":true", "\"accepted\":1234")).find("record 2: 'accepted' has the wrong type"),
            std::string::npos);
  EXPECT_NE(errorOf(replaced("\"records\":3", "\"records\":4")).find("end marker: says 4 records, the log holds 3"),
            std::string::npos);
  std::string badJson = good;
  badJson[10 + 4] = '[';  // the header JSON's first byte, after the magic line and its length
  EXPECT_NE(errorOf(badJson).find("header: not a JSON object"), std::string::npos) << errorOf(badJson);
  // A length prefix far beyond the file.
  std::string huge = good;
  huge[10] = huge[11] = huge[12] = huge[13] = '\xff';
  EXPECT_NE(errorOf(huge).find("header: JSON of 4294967295 bytes"), std::string::npos) << errorOf(huge);
  // Random damage never crashes and never reads silently wrong sizes.
  std::mt19937 rng(7);
  for (int i = 0; i < 2000; ++i) {
    std::string s = good;
    for (int k = 0; k < 3; ++k) s[rng() % s.size()] = static_cast<char>(rng());
    try {
      const CalibrationLog log = calibration::parseCalibrationLog(s, "x");
      for (const auto& r : log.records) EXPECT_TRUE(r.image.valid());
    } catch (const Error&) {
    }
  }
}

// The recorder: one record per view the Calibrator judged (CalibrationStatus::last on this very
// image), with the joints and IMU angle of the history at the exposure; a new start that
// collects again starts the log over.
TEST(CalibrationRecorder, KeepsTheJudgedImagesWithTheirExposuresJoints) {
  CalibrationRecorder recorder("head-b", "sim");
  Blackboard board;
  FrameHistory& history = board.write<FrameHistory>();
  for (int k = 0; k <= 100; ++k) {
    FrameHistory::Entry e;
    e.time = 0.01 * k;
    e.joints[HeadYaw] = 0.1 * k;
    e.imuAngle = Eigen::Vector2d(0.001 * k, 0);
    history.entries.push_back(e);
  }
  CalibrationStatus& status = board.write<CalibrationStatus>();
  ChallengeMode& mode = board.write<ChallengeMode>();
  mode.modeId = 1;
  CameraImage image = record(0, CameraId::Top, 4, 2, 5).image;
  auto see = [&](double t, int view, bool judged) {
    image.timestamp = t;
    if (judged) status.last = {view, true, "", t, 1.0, "lsd"};
    recorder.observe(image, board);
  };
  see(0.105, 1, true);
  see(0.2, 1, false);   // the same view's verdict stays: no new record
  see(0.3, 2, false);   // a new image, no verdict on it
  see(0.355, 2, true);
  ASSERT_EQ(recorder.log().records.size(), 2u);
  EXPECT_EQ(recorder.log().records[0].viewId, 1);
  EXPECT_NEAR(recorder.log().records[0].joints[HeadYaw], 1.05, 1e-9);  // interpolated at the exposure
  EXPECT_NEAR(recorder.log().records[1].imuAngle.x(), 0.0355, 1e-12);
  EXPECT_EQ(recorder.log().headId, "head-b");
  mode.modeId = 2;
  see(0.5, 3, true);
  ASSERT_EQ(recorder.log().records.size(), 1u);
  EXPECT_EQ(recorder.log().records[0].viewId, 3);
}

}  // namespace
}  // namespace nao
