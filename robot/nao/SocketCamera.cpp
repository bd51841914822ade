#include "robot/nao/SocketCamera.h"

#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <utility>

namespace nao {

SocketCamera::SocketCamera(CameraId camera, std::string path, Log log)
    : camera_(camera), path_(std::move(path)), log_(std::move(log)) {
  thread_ = std::thread([this] { receiveLoop(); });
}

SocketCamera::~SocketCamera() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

int SocketCamera::connectOnce() {
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return -1;
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::snprintf(addr.sun_path, sizeof addr.sun_path, "%s", path_.c_str());
  char hello[sizeof kSocketCameraHello];
  std::memcpy(hello, kSocketCameraHello, sizeof hello);
  hello[sizeof hello - 1] = static_cast<char>(camera_);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
      ::send(fd, hello, sizeof hello, MSG_NOSIGNAL) != static_cast<ssize_t>(sizeof hello)) {
    ::close(fd);
    return -1;
  }
  return fd;
}

bool SocketCamera::readExactly(int fd, void* data, std::size_t size) {
  auto* p = static_cast<std::uint8_t*>(data);
  while (size > 0) {
    if (stop_) return false;
    pollfd w{fd, POLLIN, 0};
    const int r = ::poll(&w, 1, 100);  // wakes to see stop_
    if (r < 0 && errno != EINTR) return false;
    if (r <= 0) continue;
    const ssize_t n = ::recv(fd, p, size, 0);
    if (n <= 0) return false;
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

void SocketCamera::receiveLoop() {
  const std::string name = std::string("camera ") + cameraName(camera_) + ": ";
  bool waitingLogged = false;
  CameraImage image;
  image.camera = camera_;
  while (!stop_) {
    const int fd = connectOnce();
    if (fd < 0) {
      if (!waitingLogged && log_) log_(name + "waiting for frames on " + path_ + " (" + std::strerror(errno) + ")");
      waitingLogged = true;
      for (int i = 0; i < 5 && !stop_; ++i) ::usleep(20000);
      continue;
    }
    if (log_) log_(name + "receiving frames from " + path_);
    {
      std::lock_guard<std::mutex> lock(sendMutex_);
      connection_ = fd;
      if (weights_) sendWeights(fd);
    }
    waitingLogged = false;
    std::string problem;
    for (;;) {
      std::uint8_t header[kSocketFrameHeaderSize];
      if (!readExactly(fd, header, sizeof header)) break;
      std::uint32_t width = 0, height = 0, reserved = 0;
      double time = 0;
      std::memcpy(&width, header + 4, 4);
      std::memcpy(&height, header + 8, 4);
      std::memcpy(&reserved, header + 12, 4);
      std::memcpy(&time, header + 16, 8);
      if (std::memcmp(header, kSocketFrameMagic, 4) != 0) problem = "not a frame header (magic)";
      else if (width < 2 || width % 2 != 0 || width > kSocketFrameMaxSide) problem = "width " + std::to_string(width) + " (even, 2.." + std::to_string(kSocketFrameMaxSide) + ")";
      else if (height < 1 || height > kSocketFrameMaxSide) problem = "height " + std::to_string(height) + " (1.." + std::to_string(kSocketFrameMaxSide) + ")";
      else if (reserved != 0) problem = "reserved word is not 0";
      else if (!std::isfinite(time) || time < 0) problem = "capture time is not a finite time";
      if (!problem.empty()) break;
      image.width = static_cast<int>(width);
      image.height = static_cast<int>(height);
      image.timestamp = time;
      image.yuyv.resize(static_cast<std::size_t>(width) * height * 2);
      if (!readExactly(fd, image.yuyv.data(), image.yuyv.size())) {
        if (!stop_) problem = "the connection ended inside a frame";
        break;
      }
      std::lock_guard<std::mutex> lock(mutex_);
      std::swap(next_, image);
      image.camera = camera_;
      ready_ = true;
      ++received_;
    }
    {
      std::lock_guard<std::mutex> lock(sendMutex_);
      connection_ = -1;
    }
    ::close(fd);
    if (stop_) break;
    if (!problem.empty()) {
      std::lock_guard<std::mutex> lock(mutex_);
      ++rejected_;
    }
    if (log_) log_(name + (problem.empty() ? "the frame socket closed" : "broken frame from " + path_ + ": " + problem) +
                   "; connecting again");
    for (int i = 0; i < 5 && !stop_; ++i) ::usleep(20000);
  }
}

void SocketCamera::setExposureWeights(const ExposureWeights& weights) {
  std::lock_guard<std::mutex> lock(sendMutex_);
  if (weights_ && *weights_ == weights) return;
  weights_ = weights;
  if (connection_ >= 0) sendWeights(connection_);
}

void SocketCamera::sendWeights(int fd) {
  std::uint8_t message[kSocketWeightsSize];
  std::memcpy(message, kSocketWeightsMagic, 4);
  std::memcpy(message + 4, weights_->cell.data(), weights_->cell.size());
  // Never blocks the motion thread; a dead connection is the receiver's to notice.
  (void)::send(fd, message, sizeof message, MSG_NOSIGNAL | MSG_DONTWAIT);
}

bool SocketCamera::grab(CameraImage& image, double /*now*/) {
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock() || !ready_) return false;  // the receiver holds it: the next cycle
  std::swap(image, next_);
  ready_ = false;
  return true;
}

long SocketCamera::received() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return received_;
}

long SocketCamera::rejected() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return rejected_;
}

}  // namespace nao
