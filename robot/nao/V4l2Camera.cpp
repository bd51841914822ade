#include "robot/nao/V4l2Camera.h"

#include <fcntl.h>
#include <linux/usb/video.h>
#include <linux/uvcvideo.h>
#include <linux/videodev2.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

namespace nao {
namespace {

class KernelV4l2Device : public V4l2Device {
 public:
  int open(const std::string& path, int flags) override { return ::open(path.c_str(), flags); }
  int close(int fd) override { return ::close(fd); }
  int ioctl(int fd, unsigned long request, void* arg) override {
    int r;
    do r = ::ioctl(fd, request, arg);
    while (r < 0 && errno == EINTR);
    return r;
  }
  void* mmap(std::size_t length, int fd, off_t offset) override {
    return ::mmap(nullptr, length, PROT_READ | PROT_WRITE, MAP_SHARED, fd, offset);
  }
  int munmap(void* address, std::size_t length) override { return ::munmap(address, length); }
  int poll(pollfd* fds, nfds_t count, int timeoutMs) override { return ::poll(fds, count, timeoutMs); }
};

std::string fourcc(std::uint32_t f) {
  std::string s;
  for (int i = 0; i < 4; ++i) {
    const char c = static_cast<char>((f >> (8 * i)) & 0xff);
    s += (c >= 0x20 && c < 0x7f) ? c : '?';
  }
  return s;
}

std::string errnoText(const char* call) { return std::string(call) + ": " + std::strerror(errno); }

}  // namespace

std::shared_ptr<V4l2Device> kernelV4l2Device() { return std::make_shared<KernelV4l2Device>(); }

void rotateYuyv180(CameraImage& image) {
  const std::size_t pairs = static_cast<std::size_t>(image.width / 2) * image.height;
  if (pairs == 0 || image.yuyv.size() < 4 * pairs) return;
  std::uint8_t* p = image.yuyv.data();
  for (std::size_t a = 0, b = pairs - 1; a < b; ++a, --b) {
    std::uint8_t* x = p + 4 * a;
    std::uint8_t* y = p + 4 * b;
    std::swap_ranges(x, x + 4, y);
  }
  for (std::size_t a = 0; a < pairs; ++a) std::swap(p[4 * a], p[4 * a + 2]);
}

V4l2Camera::V4l2Camera(std::shared_ptr<V4l2Device> device, V4l2CameraConfig config, Log log)
    : dev_(std::move(device)), config_(std::move(config)), log_(std::move(log)) {
  if (!log_) log_ = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
}

V4l2Camera::~V4l2Camera() { close(); }

bool V4l2Camera::fail(const std::string& what) {
  if (what != lastError_)
    log_(std::string("camera ") + cameraName(config_.camera) + " (" + config_.device + "): " + what);
  lastError_ = what;
  close();
  return false;
}

bool V4l2Camera::open(double now) {
  close();
  fd_ = dev_->open(config_.device, O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) return fail(errnoText("open"));

  v4l2_capability cap{};
  if (dev_->ioctl(fd_, VIDIOC_QUERYCAP, &cap) < 0) return fail(errnoText("VIDIOC_QUERYCAP"));
  const std::uint32_t caps = (cap.capabilities & V4L2_CAP_DEVICE_CAPS) ? cap.device_caps : cap.capabilities;
  if (!(caps & V4L2_CAP_VIDEO_CAPTURE)) return fail("not a video capture device");
  if (!(caps & V4L2_CAP_STREAMING)) return fail("the driver cannot stream (no V4L2_CAP_STREAMING)");

  v4l2_format fmt{};
  fmt.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  fmt.fmt.pix.width = static_cast<std::uint32_t>(config_.width);
  fmt.fmt.pix.height = static_cast<std::uint32_t>(config_.height);
  fmt.fmt.pix.pixelformat = V4L2_PIX_FMT_YUYV;
  fmt.fmt.pix.field = V4L2_FIELD_NONE;
  if (dev_->ioctl(fd_, VIDIOC_S_FMT, &fmt) < 0) return fail(errnoText("VIDIOC_S_FMT"));
  if (fmt.fmt.pix.pixelformat != V4L2_PIX_FMT_YUYV)
    return fail("the driver offers " + fourcc(fmt.fmt.pix.pixelformat) + " instead of YUYV");
  const int w = static_cast<int>(fmt.fmt.pix.width), h = static_cast<int>(fmt.fmt.pix.height);
  if (w <= 0 || h <= 0 || w % 2 != 0 || w > 4096 || h > 4096)
    return fail("the driver chose an unusable size " + std::to_string(w) + "x" + std::to_string(h));
  if (w != config_.width || h != config_.height)
    log_(std::string("camera ") + cameraName(config_.camera) + ": asked for " + std::to_string(config_.width) + "x" +
         std::to_string(config_.height) + ", the driver delivers " + std::to_string(w) + "x" + std::to_string(h));
  width_ = w;
  height_ = h;
  stride_ = std::max<int>(static_cast<int>(fmt.fmt.pix.bytesperline), 2 * w);

  v4l2_streamparm parm{};
  parm.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  parm.parm.capture.timeperframe.numerator = 1;
  parm.parm.capture.timeperframe.denominator = static_cast<std::uint32_t>(config_.fps);
  if (dev_->ioctl(fd_, VIDIOC_S_PARM, &parm) < 0) {
    log_(std::string("camera ") + cameraName(config_.camera) + ": cannot set the frame rate (" + std::strerror(errno) + ")");
  } else {
    const auto& tpf = parm.parm.capture.timeperframe;
    if (tpf.numerator != 0 && tpf.denominator != 0 &&
        static_cast<std::uint64_t>(tpf.denominator) != static_cast<std::uint64_t>(config_.fps) * tpf.numerator)
      log_(std::string("camera ") + cameraName(config_.camera) + ": the driver runs at " + std::to_string(tpf.denominator) +
           "/" + std::to_string(tpf.numerator) + " fps");
  }

  v4l2_requestbuffers req{};
  req.count = static_cast<std::uint32_t>(std::max(config_.buffers, 2));
  req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  req.memory = V4L2_MEMORY_MMAP;
  if (dev_->ioctl(fd_, VIDIOC_REQBUFS, &req) < 0) return fail(errnoText("VIDIOC_REQBUFS"));
  if (req.count < 2) return fail("the driver gives only " + std::to_string(req.count) + " buffer(s), 2 are needed");
  buffers_.resize(req.count);
  for (std::uint32_t i = 0; i < req.count; ++i) {
    v4l2_buffer b{};
    b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    b.memory = V4L2_MEMORY_MMAP;
    b.index = i;
    if (dev_->ioctl(fd_, VIDIOC_QUERYBUF, &b) < 0) return fail(errnoText("VIDIOC_QUERYBUF"));
    if (b.length < static_cast<std::uint32_t>(stride_) * static_cast<std::uint32_t>(height_))
      return fail("buffer " + std::to_string(i) + " holds " + std::to_string(b.length) + " bytes, a frame needs " +
                  std::to_string(stride_ * height_));
    void* p = dev_->mmap(b.length, fd_, static_cast<off_t>(b.m.offset));
    if (p == MAP_FAILED) return fail(errnoText("mmap"));
    buffers_[i] = {p, b.length};
    if (!queue(i)) return fail(errnoText("VIDIOC_QBUF"));
  }
  int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  if (dev_->ioctl(fd_, VIDIOC_STREAMON, &type) < 0) return fail(errnoText("VIDIOC_STREAMON"));
  streaming_ = true;
  setControls();  // some sensor drivers take controls only while streaming
  lastFrame_ = now;
  if (everOpened_) ++stats_.reopens;
  everOpened_ = true;
  lastError_.clear();
  log_(std::string("camera ") + cameraName(config_.camera) + ": streaming " + std::to_string(width_) + "x" +
       std::to_string(height_) + " YUYV at " + std::to_string(config_.fps) + " Hz, " + std::to_string(buffers_.size()) +
       " mmap buffers" + (config_.rotate180 ? (softwareRotation_ ? ", rotated in software" : ", flipped by the driver") : ""));
  return true;
}

void V4l2Camera::close() {
  if (fd_ >= 0 && streaming_) {
    int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    dev_->ioctl(fd_, VIDIOC_STREAMOFF, &type);
  }
  streaming_ = false;
  for (auto& b : buffers_)
    if (b.start && b.start != MAP_FAILED) dev_->munmap(b.start, b.length);
  if (fd_ >= 0 && !buffers_.empty()) {
    v4l2_requestbuffers req{};
    req.count = 0;
    req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    req.memory = V4L2_MEMORY_MMAP;
    dev_->ioctl(fd_, VIDIOC_REQBUFS, &req);
  }
  buffers_.clear();
  if (fd_ >= 0) dev_->close(fd_);
  fd_ = -1;
}

bool V4l2Camera::queue(std::uint32_t index) {
  v4l2_buffer b{};
  b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  b.memory = V4L2_MEMORY_MMAP;
  b.index = index;
  return dev_->ioctl(fd_, VIDIOC_QBUF, &b) == 0;
}

bool V4l2Camera::setControl(std::uint32_t id, int value, const char* name, bool required) {
  const std::string prefix = std::string("camera ") + cameraName(config_.camera) + ": ";
  v4l2_queryctrl q{};
  q.id = id;
  if (dev_->ioctl(fd_, VIDIOC_QUERYCTRL, &q) < 0 || (q.flags & V4L2_CTRL_FLAG_DISABLED)) {
    if (required) log_(prefix + "the driver has no " + name + " control");
    return false;
  }
  int v = std::clamp(value, q.minimum, q.maximum);
  if (q.step > 1) v = q.minimum + (v - q.minimum) / q.step * q.step;
  if (v != value) log_(prefix + name + " " + std::to_string(value) + " is outside the driver's range, using " + std::to_string(v));
  v4l2_control c{};
  c.id = id;
  c.value = v;
  if (dev_->ioctl(fd_, VIDIOC_S_CTRL, &c) < 0) {
    log_(prefix + "setting " + name + " failed: " + std::strerror(errno));
    return false;
  }
  v4l2_control back{};
  back.id = id;
  if (dev_->ioctl(fd_, VIDIOC_G_CTRL, &back) == 0 && back.value != v)
    log_(prefix + name + ": set " + std::to_string(v) + ", the driver reports " + std::to_string(back.value));
  return true;
}

void V4l2Camera::setControls() {
  softwareRotation_ = false;
  if (config_.rotate180) {
    const bool h = setControl(V4L2_CID_HFLIP, 1, "hflip", false);
    const bool v = h && setControl(V4L2_CID_VFLIP, 1, "vflip", false);
    if (!v) {
      if (h) setControl(V4L2_CID_HFLIP, 0, "hflip", false);
      softwareRotation_ = true;
    }
  }
  const CameraControls& c = config_.controls;
  // Automatic modes first: a manual value is ignored while its automatic mode is on.
  if (c.autoExposure)
    setControl(V4L2_CID_EXPOSURE_AUTO, *c.autoExposure ? V4L2_EXPOSURE_AUTO : V4L2_EXPOSURE_MANUAL, "auto exposure", true);
  if (c.exposure) setControl(V4L2_CID_EXPOSURE_ABSOLUTE, *c.exposure, "exposure", true);
  if (c.gain) setControl(V4L2_CID_GAIN, *c.gain, "gain", true);
  if (c.autoWhiteBalance) setControl(V4L2_CID_AUTO_WHITE_BALANCE, *c.autoWhiteBalance ? 1 : 0, "auto white balance", true);
  if (c.whiteBalance) setControl(V4L2_CID_WHITE_BALANCE_TEMPERATURE, *c.whiteBalance, "white balance", true);
  writeExposureWeights();
}

std::array<std::uint8_t, 17> naoExposureWeightsPayload(const ExposureWeights& weights, int width, int height) {
  const auto hi = [](int v) { return static_cast<std::uint8_t>((v >> 8) & 0xff); };
  const auto lo = [](int v) { return static_cast<std::uint8_t>(v & 0xff); };
  std::array<std::uint8_t, 17> p{1, 0, 0, 0, 0, hi(width), lo(width), hi(height), lo(height)};
  for (std::size_t k = 0; k < 8; ++k)
    p[9 + k] = static_cast<std::uint8_t>((std::min<int>(weights.cell[2 * k], ExposureWeights::kMax)) |
                                         (std::min<int>(weights.cell[2 * k + 1], ExposureWeights::kMax) << 4));
  return p;
}

void V4l2Camera::setExposureWeights(const ExposureWeights& weights) {
  if (exposureWeights_ && *exposureWeights_ == weights) return;
  exposureWeights_ = weights;
  if (streaming_) writeExposureWeights();
}

void V4l2Camera::writeExposureWeights() {
  if (!exposureWeights_ || exposureWeightsRefused_ || fd_ < 0) return;
  std::array<std::uint8_t, 17> payload = naoExposureWeightsPayload(*exposureWeights_, width_, height_);
  uvc_xu_control_query q{};
  q.unit = kNaoCameraExtensionUnit;
  q.selector = kNaoExposureWeightsSelector;
  q.query = UVC_SET_CUR;
  q.size = static_cast<__u16>(payload.size());
  q.data = payload.data();
  if (dev_->ioctl(fd_, UVCIOC_CTRL_QUERY, &q) < 0) {
    exposureWeightsRefused_ = true;
    log_(std::string("camera ") + cameraName(config_.camera) + " (" + config_.device +
         "): setting the auto exposure weights failed (" + std::strerror(errno) +
         "); the camera meters its own way from now on");
  }
}

void V4l2Camera::recover(const std::string& what, double now) {
  ++stats_.errors;
  log_(std::string("camera ") + cameraName(config_.camera) + " (" + config_.device + "): " + what + "; reopening");
  lastError_ = what;
  close();
  if (!open(now)) nextOpen_ = now + config_.reopenInterval;
}

bool V4l2Camera::grab(CameraImage& image, double now) {
  if (!streaming_) {
    if (now < nextOpen_) return false;
    if (!open(now)) {
      nextOpen_ = now + config_.reopenInterval;
      return false;
    }
  }
  pollfd p{fd_, POLLIN, 0};
  const int n = dev_->poll(&p, 1, 0);
  if (n < 0) {
    if (errno != EINTR) recover(errnoText("poll"), now);
    return false;
  }
  if (n == 0 || !(p.revents & POLLIN)) {
    if (n > 0 && (p.revents & (POLLERR | POLLHUP | POLLNVAL)))
      recover("the device reported an error (poll revents " + std::to_string(p.revents) + ")", now);
    else if (now - lastFrame_ > config_.frameTimeout)
      recover("no frame for " + std::to_string(static_cast<int>((now - lastFrame_) * 1000)) + " ms", now);
    return false;
  }

  // Take every ready frame and keep the newest: the program wants the latest image.
  int newest = -1;
  v4l2_buffer got{};
  for (;;) {
    v4l2_buffer b{};
    b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    b.memory = V4L2_MEMORY_MMAP;
    if (dev_->ioctl(fd_, VIDIOC_DQBUF, &b) < 0) {
      if (errno == EAGAIN) break;
      if (errno == EINTR) continue;
      recover(errnoText("VIDIOC_DQBUF"), now);
      return false;
    }
    if (b.index >= buffers_.size()) {
      recover("the driver returned buffer " + std::to_string(b.index) + " of " + std::to_string(buffers_.size()), now);
      return false;
    }
    if (newest >= 0) {
      ++stats_.dropped;
      if (!queue(static_cast<std::uint32_t>(newest))) {
        recover(errnoText("VIDIOC_QBUF"), now);
        return false;
      }
    }
    newest = static_cast<int>(b.index);
    got = b;
  }
  if (newest < 0) return false;

  const std::size_t need = static_cast<std::size_t>(stride_) * (height_ - 1) + 2 * static_cast<std::size_t>(width_);
  const std::size_t used = got.bytesused ? got.bytesused : got.length;
  const bool damaged = (got.flags & V4L2_BUF_FLAG_ERROR) || used < need;
  if (!damaged) {
    image.camera = config_.camera;
    image.width = width_;
    image.height = height_;
    image.yuyv.resize(static_cast<std::size_t>(width_) * height_ * 2);
    const auto* src = static_cast<const std::uint8_t*>(buffers_[newest].start);
    for (int r = 0; r < height_; ++r)
      std::memcpy(image.yuyv.data() + static_cast<std::size_t>(r) * width_ * 2, src + static_cast<std::size_t>(r) * stride_,
                  static_cast<std::size_t>(width_) * 2);
    const bool monotonic = (got.flags & V4L2_BUF_FLAG_TIMESTAMP_MASK) == V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC;
    image.timestamp = monotonic ? got.timestamp.tv_sec + got.timestamp.tv_usec * 1e-6 : now;
    if (softwareRotation_) rotateYuyv180(image);
  } else {
    ++stats_.dropped;
  }
  if (!queue(static_cast<std::uint32_t>(newest))) {
    recover(errnoText("VIDIOC_QBUF"), now);
    return false;
  }
  if (damaged) return false;  // a damaged stream reopens after frameTimeout
  lastFrame_ = now;
  ++stats_.frames;
  return true;
}

}  // namespace nao
