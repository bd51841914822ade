// FileCamera (--cameras files:DIR): the files in name order, looping, one frame per period at
// the times they are due, each decoded by the given decoder in the camera's own thread; a file
// that does not decode is skipped (and logged once). The decoder here stands in for PNG/JPEG decoding: it writes
// the file's index into the image, so the order is checked from the frames themselves.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "robot/Error.h"
#include "robot/nao/FileCamera.h"
#include "robot/nao/ImageFiles.h"

namespace nao {
namespace {

namespace fs = std::filesystem;

CameraImage decodeIndex(const std::string& path, CameraId) {
  const std::string name = fs::path(path).stem().string();  // "f<index>"
  if (name == "broken") throw Error(path, "not a readable PNG or JPEG image");
  CameraImage image;
  image.width = 4;
  image.height = 2;
  image.yuyv.assign(16, static_cast<std::uint8_t>(std::stoi(name.substr(1))));
  return image;
}

// Waits (briefly) until a frame due at `now` has been decoded.
bool grabWithin(FileCamera& camera, CameraImage& image, double now) {
  for (int i = 0; i < 2000; ++i) {
    if (camera.grab(image, now)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

TEST(FileCamera, FramesInOrderLoopingAtTheirDueTimes) {
  const double period = 1.0 / 30;
  FileCamera camera(CameraId::Bottom, {"/x/f0.png", "/x/f1.png", "/x/f2.png"}, decodeIndex, 100.0, period);
  CameraImage image;
  EXPECT_FALSE(camera.grab(image, 99.99));  // not due yet
  for (int frame = 0; frame < 7; ++frame) {
    const double due = 100.0 + frame * period;
    EXPECT_FALSE(camera.grab(image, due - 0.001)) << frame;
    ASSERT_TRUE(grabWithin(camera, image, due + 0.004)) << frame;
    EXPECT_EQ(image.yuyv[0], frame % 3) << "frame " << frame;  // f0, f1, f2, f0, ...
    EXPECT_EQ(image.camera, CameraId::Bottom);
    EXPECT_DOUBLE_EQ(image.timestamp, due);
    EXPECT_FALSE(camera.grab(image, due + 0.005)) << "one frame per period";
  }
}

// A looping replay decodes each file once: later rounds come from the camera's cache.
TEST(FileCamera, EachFileIsDecodedOnceWhileTheFramesFitTheCache) {
  std::atomic<int> decodes{0};
  auto counting = [&decodes](const std::string& path, CameraId camera) {
    ++decodes;
    return decodeIndex(path, camera);
  };
  const double period = 1.0 / 30;
  FileCamera camera(CameraId::Top, {"/x/f0.png", "/x/f1.png"}, counting, 0.0, period);
  CameraImage image;
  for (int frame = 0; frame < 8; ++frame) {
    ASSERT_TRUE(grabWithin(camera, image, frame * period + 0.001)) << frame;
    EXPECT_EQ(image.yuyv[0], frame % 2) << frame;
  }
  EXPECT_EQ(decodes.load(), 2);
}

TEST(FileCamera, AfterAStallTheNextFrameIsNotABurst) {
  const double period = 0.1;
  FileCamera camera(CameraId::Top, {"/x/f0.png", "/x/f1.png"}, decodeIndex, 0.0, period);
  CameraImage image;
  ASSERT_TRUE(grabWithin(camera, image, 0.0));
  ASSERT_TRUE(grabWithin(camera, image, 5.0));  // 4.9 s late: one frame, stamped when it was due
  EXPECT_DOUBLE_EQ(image.timestamp, 0.1);
  EXPECT_FALSE(camera.grab(image, 5.0 + 0.01));
  EXPECT_TRUE(grabWithin(camera, image, 5.0 + period));
}

TEST(FileCamera, ABrokenFileIsSkippedAndLogged) {
  std::vector<std::string> log;
  std::mutex logMutex;
  {
    FileCamera camera(CameraId::Top, {"/x/broken.png", "/x/f7.png"}, decodeIndex, 0.0, 0.05,
                      [&](const std::string& line) {
                        std::lock_guard<std::mutex> lock(logMutex);
                        log.push_back(line);
                      });
    CameraImage image;
    for (int frame = 0; frame < 3; ++frame) {
      ASSERT_TRUE(grabWithin(camera, image, frame * 0.05));
      EXPECT_EQ(image.yuyv[0], 7);
    }
  }
  ASSERT_EQ(log.size(), 1u) << "logged once, not on every pass";
  EXPECT_EQ(log[0], "camera top: skipped /x/broken.png: not a readable PNG or JPEG image");
}

TEST(FileCamera, OnlyBrokenFilesGiveNoFrames) {
  FileCamera camera(CameraId::Top, {"/x/broken.png"}, decodeIndex, 0.0, 0.05, [](const std::string&) {});
  CameraImage image;
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_FALSE(camera.grab(image, 1.0));
}

// --lockstep: a due frame is waited for, however slow its decoding, and the schedule is kept
// after a stall, so that a replay hands the same frames to the same cycles on any machine.
TEST(FileCamera, InLockstepADueFrameIsWaitedForAndTheScheduleKept) {
  const double period = 1.0 / 30;
  auto slow = [](const std::string& path, CameraId c) {
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    return decodeIndex(path, c);
  };
  FileCamera camera(CameraId::Top, {"/x/f0.png", "/x/f1.png", "/x/f2.png"}, slow, 0.0, period, {}, true);
  CameraImage image;
  EXPECT_FALSE(camera.grab(image, -0.001));  // not due yet: no wait
  ASSERT_TRUE(camera.grab(image, 0.0));      // due: one call, however long the decoding takes
  EXPECT_EQ(image.yuyv[0], 0);
  EXPECT_DOUBLE_EQ(image.timestamp, 0.0);
  ASSERT_TRUE(camera.grab(image, 10.0));  // long after: the next frame on its own schedule
  EXPECT_EQ(image.yuyv[0], 1);
  EXPECT_DOUBLE_EQ(image.timestamp, period);
  ASSERT_TRUE(camera.grab(image, 10.0));
  EXPECT_EQ(image.yuyv[0], 2);
  EXPECT_DOUBLE_EQ(image.timestamp, 2 * period);
  // Only broken files: no wait forever, no frame.
  FileCamera broken(CameraId::Top, {"/x/broken.png"}, decodeIndex, 0.0, period, [](const std::string&) {}, true);
  EXPECT_FALSE(broken.grab(image, 1.0));
}

TEST(ImageFiles, PngAndJpegInNameOrder) {
  const fs::path dir = fs::path(::testing::TempDir()) / "file_camera_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "sub.png");
  for (const char* name : {"b.JPG", "a.png", "c.jpeg", "notes.txt", "d.yuv"}) std::ofstream(dir / name) << "x";
  const auto files = imageFilesIn(dir.string());
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(fs::path(files[0]).filename(), "a.png");
  EXPECT_EQ(fs::path(files[1]).filename(), "b.JPG");
  EXPECT_EQ(fs::path(files[2]).filename(), "c.jpeg");
  EXPECT_TRUE(imageFilesIn((dir / "missing").string()).empty());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace nao
