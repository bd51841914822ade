#pragma once
// A NAO V6 camera through V4L2: YUYV at a set resolution and 30 Hz, mmap buffers, kernel
// timestamps, exposure / gain / white balance controls, and recovery after a device error
// (close, reopen, carry on). All kernel calls go through V4l2Device so that tests can stand
// in for the driver; kernelV4l2Device() is the real one.
#include <poll.h>
#include <sys/types.h>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "robot/CameraImage.h"
#include "robot/nao/CameraSource.h"

namespace nao {

// The system calls a V4L2 capture needs, with their POSIX meaning: -1 (or MAP_FAILED) and
// errno on failure.
class V4l2Device {
 public:
  virtual ~V4l2Device() = default;
  virtual int open(const std::string& path, int flags) = 0;
  virtual int close(int fd) = 0;
  virtual int ioctl(int fd, unsigned long request, void* arg) = 0;
  virtual void* mmap(std::size_t length, int fd, off_t offset) = 0;  // PROT_READ | PROT_WRITE, MAP_SHARED
  virtual int munmap(void* address, std::size_t length) = 0;
  virtual int poll(pollfd* fds, nfds_t count, int timeoutMs) = 0;
};

std::shared_ptr<V4l2Device> kernelV4l2Device();

// Controls left unset stay as the driver has them.
struct CameraControls {
  std::optional<bool> autoExposure;
  std::optional<int> exposure;  // V4L2_CID_EXPOSURE_ABSOLUTE (driver units, 100 us on the NAO)
  std::optional<int> gain;      // V4L2_CID_GAIN
  std::optional<bool> autoWhiteBalance;
  std::optional<int> whiteBalance;  // V4L2_CID_WHITE_BALANCE_TEMPERATURE (K)
};

struct V4l2CameraConfig {
  CameraId camera = CameraId::Top;
  std::string device = "/dev/video-top";
  int width = 640, height = 480;
  int fps = 30;
  int buffers = 4;
  // Deliver the image rotated by 180 deg (the NAO's top camera is mounted upside down): the
  // driver's flip controls when it has them, otherwise in software.
  bool rotate180 = false;
  CameraControls controls;
  double frameTimeout = 1.0;    // s without a frame while streaming: reopen
  double reopenInterval = 1.0;  // s between attempts to open a failed device
};

class V4l2Camera : public CameraSource {
 public:
  using Log = std::function<void(const std::string&)>;
  V4l2Camera(std::shared_ptr<V4l2Device> device, V4l2CameraConfig config, Log log = {});
  ~V4l2Camera() override;
  V4l2Camera(const V4l2Camera&) = delete;
  V4l2Camera& operator=(const V4l2Camera&) = delete;

  // Opens the device, negotiates the format and starts streaming. False (lastError() says
  // why, logged) when it failed; grab() tries again every reopenInterval.
  bool open(double now);
  void close();

  // Non-blocking: true when a new frame arrived since the last call; `image` then holds the
  // newest one (older ready frames are dropped), timestamp = the kernel's capture time in
  // CLOCK_MONOTONIC seconds. now: CLOCK_MONOTONIC seconds, for the recovery timing.
  bool grab(CameraImage& image, double now) override;
  // Written to the camera now when it streams, and again after every reopen. A camera without
  // the NAO's extension unit (any other UVC camera) refuses: logged once, then left alone.
  void setExposureWeights(const ExposureWeights& weights) override;

  bool streaming() const { return streaming_; }
  int width() const { return width_; }
  int height() const { return height_; }
  const std::string& lastError() const { return lastError_; }
  const V4l2CameraConfig& config() const { return config_; }

  struct Stats {
    std::uint64_t frames = 0, dropped = 0, errors = 0, reopens = 0;
  };
  const Stats& stats() const { return stats_; }
  bool softwareRotation() const { return softwareRotation_; }

 private:
  struct Buffer {
    void* start = nullptr;
    std::size_t length = 0;
  };
  bool fail(const std::string& what);
  void recover(const std::string& what, double now);
  void setControls();
  void writeExposureWeights();
  bool setControl(std::uint32_t id, int value, const char* name, bool required);
  bool queue(std::uint32_t index);

  std::shared_ptr<V4l2Device> dev_;
  V4l2CameraConfig config_;
  Log log_;
  int fd_ = -1;
  bool streaming_ = false;
  std::vector<Buffer> buffers_;
  int width_ = 0, height_ = 0, stride_ = 0;
  bool softwareRotation_ = false;
  double lastFrame_ = 0, nextOpen_ = 0;
  bool everOpened_ = false;
  std::optional<ExposureWeights> exposureWeights_;  // set by the program; unset: the camera's own
  bool exposureWeightsRefused_ = false;
  std::string lastError_;
  Stats stats_;
};

// The NAO V6 camera's auto exposure window and weights: UVC extension unit 3, selector 9, 17
// bytes: 1 (enabled), the window's first column, first row, last column, last row (16 bit each,
// high byte first; the whole image), then the 16 weights of the 4 x 4 cells, two per byte in
// row-major order, the even cell in the low nibble (as the OV5640's AEC weight registers
// 0x5688..0x568F hold them).
inline constexpr std::uint8_t kNaoCameraExtensionUnit = 3;
inline constexpr std::uint8_t kNaoExposureWeightsSelector = 9;
std::array<std::uint8_t, 17> naoExposureWeightsPayload(const ExposureWeights& weights, int width, int height);

// Rotates a YUYV image by 180 deg in place (pairs reversed, Y0/Y1 swapped within each pair).
void rotateYuyv180(CameraImage& image);

}  // namespace nao
