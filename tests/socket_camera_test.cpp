// SocketCamera (--cameras socket:PATH): connects to a peer's listening socket (waiting while
// there is none), names its camera, receives frames in its own thread and hands the newest one
// over; a broken frame is named in one log line, the connection dropped and made again. The
// peer here is the test itself, writing the wire of robot/nao/SocketCamera.h byte by byte.
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "robot/nao/SocketCamera.h"

namespace nao {
namespace {

namespace fs = std::filesystem;

int listenOn(const std::string& path) {
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::snprintf(addr.sun_path, sizeof addr.sun_path, "%s", path.c_str());
  ::unlink(path.c_str());
  EXPECT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  EXPECT_EQ(::listen(fd, 2), 0);
  return fd;
}

// Accepts one camera and returns its connection after checking the hello.
int acceptCamera(int listener, int expectedCamera) {
  pollfd p{listener, POLLIN, 0};
  if (::poll(&p, 1, 5000) <= 0) return -1;
  const int c = ::accept(listener, nullptr, nullptr);
  char hello[8] = {};
  EXPECT_EQ(::recv(c, hello, 8, MSG_WAITALL), 8);
  EXPECT_EQ(std::memcmp(hello, "NAOCAM1", 7), 0);
  EXPECT_EQ(hello[7], expectedCamera);
  return c;
}

std::vector<std::uint8_t> frame(std::uint32_t width, std::uint32_t height, double time, std::uint8_t fill,
                                const char* magic = "NAOF") {
  std::vector<std::uint8_t> b(24 + static_cast<std::size_t>(width) * height * 2, fill);
  std::memcpy(b.data(), magic, 4);
  const std::uint32_t zero = 0;
  std::memcpy(b.data() + 4, &width, 4);
  std::memcpy(b.data() + 8, &height, 4);
  std::memcpy(b.data() + 12, &zero, 4);
  std::memcpy(b.data() + 16, &time, 8);
  return b;
}

void sendAll(int fd, const std::vector<std::uint8_t>& b) {
  std::size_t done = 0;
  while (done < b.size()) {
    const ssize_t n = ::send(fd, b.data() + done, b.size() - done, MSG_NOSIGNAL);
    ASSERT_GT(n, 0);
    done += static_cast<std::size_t>(n);
  }
}

bool grabWithin(SocketCamera& camera, CameraImage& image) {
  for (int i = 0; i < 3000; ++i) {
    if (camera.grab(image, 0)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

struct Log {
  std::mutex mutex;
  std::vector<std::string> lines;
  SocketCamera::Log sink() {
    return [this](const std::string& l) {
      std::lock_guard<std::mutex> lock(mutex);
      lines.push_back(l);
    };
  }
  bool has(const std::string& text) {
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto& l : lines)
      if (l.find(text) != std::string::npos) return true;
    return false;
  }
};

fs::path socketPath(const char* name) {
  const fs::path dir = fs::path(::testing::TempDir()) / "socket_camera_test";
  fs::create_directories(dir);
  return dir / name;
}

TEST(SocketCamera, WaitsForThePeerThenHandsOverTheNewestFrameWithItsCaptureTime) {
  const std::string path = socketPath("a.sock").string();
  ::unlink(path.c_str());
  Log log;
  SocketCamera camera(CameraId::Bottom, path, log.sink());
  CameraImage image;
  EXPECT_FALSE(camera.grab(image, 0));  // nobody there: no frame, no block
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  EXPECT_TRUE(log.has("camera bottom: waiting for frames on " + path));

  const int listener = listenOn(path);  // the peer appears later
  const int c = acceptCamera(listener, 1);
  ASSERT_GE(c, 0);
  sendAll(c, frame(4, 2, 12.5, 7));
  ASSERT_TRUE(grabWithin(camera, image));
  EXPECT_EQ(image.camera, CameraId::Bottom);
  EXPECT_EQ(image.width, 4);
  EXPECT_EQ(image.height, 2);
  EXPECT_TRUE(image.valid());
  EXPECT_DOUBLE_EQ(image.timestamp, 12.5);
  EXPECT_EQ(image.yuyv[0], 7);
  EXPECT_FALSE(camera.grab(image, 0)) << "each frame once";

  // Two frames before the next grab: the newer one wins.
  sendAll(c, frame(4, 2, 12.6, 8));
  sendAll(c, frame(4, 2, 12.7, 9));
  for (int i = 0; i < 3000 && camera.received() < 3; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ASSERT_TRUE(grabWithin(camera, image));
  EXPECT_DOUBLE_EQ(image.timestamp, 12.7);
  EXPECT_EQ(image.yuyv[5], 9);
  EXPECT_EQ(camera.received(), 3);
  EXPECT_EQ(camera.rejected(), 0);
  ::close(c);
  ::close(listener);
}

TEST(SocketCamera, ABrokenFrameIsNamedAndTheConnectionMadeAgain) {
  const std::string path = socketPath("b.sock").string();
  const int listener = listenOn(path);
  Log log;
  SocketCamera camera(CameraId::Top, path, log.sink());
  struct Case {
    std::vector<std::uint8_t> bytes;
    std::string problem;
  };
  const Case cases[] = {{frame(4, 2, 1.0, 0, "JUNK"), "not a frame header (magic)"},
                        {frame(3, 2, 1.0, 0), "width 3 (even, 2..4096)"},
                        {frame(4, 0, 1.0, 0), "height 0 (1..4096)"},
                        {frame(4, 2, std::nan(""), 0), "capture time is not a finite time"}};
  for (const Case& k : cases) {
    const int c = acceptCamera(listener, 0);
    ASSERT_GE(c, 0) << k.problem;
    sendAll(c, k.bytes);
    // The camera hangs up and connects again: the next accept is its new connection.
    const int again = acceptCamera(listener, 0);
    ASSERT_GE(again, 0) << k.problem;
    EXPECT_TRUE(log.has("camera top: broken frame from " + path + ": " + k.problem + "; connecting again")) << k.problem;
    ::close(c);
    ::close(again);
  }
  // A frame cut short is named too; a good frame after all that comes through.
  {
    const int c = acceptCamera(listener, 0);
    std::vector<std::uint8_t> cut = frame(640, 480, 2.0, 1);
    cut.resize(1000);
    sendAll(c, cut);
    ::close(c);
    const int again = acceptCamera(listener, 0);
    ASSERT_GE(again, 0);
    EXPECT_TRUE(log.has("the connection ended inside a frame"));
    sendAll(again, frame(4, 2, 3.0, 5));
    CameraImage image;
    ASSERT_TRUE(grabWithin(camera, image)) << "a good frame after the broken ones";
    EXPECT_DOUBLE_EQ(image.timestamp, 3.0);
    ::close(again);
  }
  EXPECT_EQ(camera.rejected(), 5);
  ::close(listener);
}

}  // namespace
}  // namespace nao

namespace nao {
namespace {

// The exposure weights the program chooses go the other way, to the peer that renders: after
// the hello when set before, on each change, and again on a new connection.
TEST(SocketCamera, SendsTheProgramsExposureWeightsOnEachChangeAndAfterAReconnect) {
  const std::string path = socketPath("w.sock").string();
  const int listener = listenOn(path);
  Log log;
  SocketCamera camera(CameraId::Top, path, log.sink());
  ExposureWeights w;
  for (int k = 0; k < 16; ++k) w.cell[static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(k < 4 ? 0 : 15);
  camera.setExposureWeights(w);  // before the peer took the connection
  auto readWeights = [](int fd, ExposureWeights& out) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 3000) <= 0) return false;
    std::uint8_t m[kSocketWeightsSize];
    if (::recv(fd, m, sizeof m, MSG_WAITALL) != static_cast<ssize_t>(sizeof m)) return false;
    if (std::memcmp(m, "NAOW", 4) != 0) return false;
    std::memcpy(out.cell.data(), m + 4, 16);
    return true;
  };
  const int c = acceptCamera(listener, 0);
  ASSERT_GE(c, 0);
  ExposureWeights got;
  ASSERT_TRUE(readWeights(c, got));
  EXPECT_EQ(got, w);
  ExposureWeights w2 = w;
  w2.cell[0] = 7;
  camera.setExposureWeights(w2);
  ASSERT_TRUE(readWeights(c, got));
  EXPECT_EQ(got, w2);
  camera.setExposureWeights(w2);  // unchanged: nothing sent
  pollfd p{c, POLLIN, 0};
  EXPECT_EQ(::poll(&p, 1, 100), 0);
  ::close(c);  // the peer goes away; the camera connects again and says them again
  const int again = acceptCamera(listener, 0);
  ASSERT_GE(again, 0);
  ASSERT_TRUE(readWeights(again, got));
  EXPECT_EQ(got, w2);
  ::close(again);
  ::close(listener);
}

}  // namespace
}  // namespace nao
