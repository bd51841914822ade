// V4L2 capture against a test double of the kernel's ioctl layer: a small fake driver that
// keeps V4L2's buffer queue semantics (REQBUFS, QUERYBUF, mmap, QBUF, DQBUF, STREAMON/OFF),
// negotiates formats like a driver (it may pick another size or pixel format), has controls
// with ranges, and can fail on demand. No camera is needed; the real device path is only
// exercised as far as opening a device that does not exist.
#include <errno.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <linux/usb/video.h>
#include <linux/uvcvideo.h>
#include <linux/videodev2.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#include <cstring>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "robot/nao/NaoBackend.h"
#include "robot/nao/V4l2Camera.h"

namespace nao {
namespace {

class FakeDriver : public V4l2Device {
 public:
  // What the driver offers.
  std::string path = "/dev/video-top";
  std::uint32_t pixelFormat = V4L2_PIX_FMT_YUYV;
  std::uint32_t maxWidth = 1280, maxHeight = 960;
  std::uint32_t padding = 0;  // bytes per line beyond width * 2
  std::uint32_t maxBuffers = 8;
  bool flipControls = true;
  bool naoExtensionUnit = true;  // the NAO camera's UVC extension unit (auto exposure weights)
  struct Control {
    int min, max, step, value;
  };
  std::map<std::uint32_t, Control> controls = {
      {V4L2_CID_EXPOSURE_AUTO, {0, 3, 1, 0}},        {V4L2_CID_EXPOSURE_ABSOLUTE, {1, 2500, 1, 300}},
      {V4L2_CID_GAIN, {0, 1023, 1, 32}},             {V4L2_CID_AUTO_WHITE_BALANCE, {0, 1, 1, 1}},
      {V4L2_CID_WHITE_BALANCE_TEMPERATURE, {2700, 6500, 100, 4500}}, {V4L2_CID_HFLIP, {0, 1, 1, 0}},
      {V4L2_CID_VFLIP, {0, 1, 1, 0}}};

  // Failures to inject.
  int openErrno = 0;    // every open fails with this while non-zero
  int dqbufErrno = 0;   // the next DQBUF fails with this
  bool pollError = false;
  // The clock the driver stamps its buffers with (UVC and most sensor drivers: monotonic).
  std::uint32_t timestampClock = V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC;

  // What happened.
  std::vector<std::string> calls;
  int fdOpen = 0, mapped = 0, opens = 0;
  bool streaming = false;
  v4l2_fract timePerFrame{};
  std::vector<std::pair<std::uint32_t, int>> setControls;
  std::vector<std::vector<std::uint8_t>> exposureWeightWrites;  // selector 9's payloads, in order

  // The frames the "sensor" captured: fills the first queued buffer (false if none queued).
  bool capture(std::uint8_t seed, double timestamp, std::uint32_t flags = 0, std::uint32_t bytesused = 0) {
    if (!streaming || queued_.empty()) return false;
    const std::uint32_t i = queued_.front();
    queued_.pop_front();
    Buffer& b = buffers_[i];
    for (std::uint32_t r = 0; r < height_; ++r)
      for (std::uint32_t x = 0; x < width_ * 2; ++x)
        b.memory[r * stride() + x] = static_cast<std::uint8_t>(seed + r * 3 + x);
    b.bytesused = bytesused ? bytesused : stride() * height_;
    b.flags = flags | timestampClock;
    b.timestamp.tv_sec = static_cast<long>(timestamp);
    b.timestamp.tv_usec = static_cast<long>((timestamp - static_cast<double>(b.timestamp.tv_sec)) * 1e6 + 0.5);
    done_.push_back(i);
    return true;
  }
  std::size_t queued() const { return queued_.size(); }
  std::uint32_t stride() const { return width_ * 2 + padding; }
  int controlValue(std::uint32_t id) const { return controls.at(id).value; }
  bool owns(const void* address) const {
    for (const auto& b : buffers_)
      if (b.memory.data() == address) return true;
    return false;
  }

  int open(const std::string& p, int flags) override {
    calls.push_back("open");
    ++opens;
    if (openErrno) return errno = openErrno, -1;
    if (p != path) return errno = ENOENT, -1;
    if (!(flags & O_NONBLOCK)) return errno = EINVAL, -1;  // the camera must never block a cycle
    if (fdOpen) return errno = EBUSY, -1;
    fdOpen = 1;
    return kFd;
  }
  int close(int fd) override {
    calls.push_back("close");
    if (fd != kFd || !fdOpen) return errno = EBADF, -1;
    fdOpen = 0;
    streaming = false;
    buffers_.clear();
    queued_.clear();
    done_.clear();
    return 0;
  }
  void* mmap(std::size_t length, int fd, off_t offset) override {
    calls.push_back("mmap");
    const std::size_t i = static_cast<std::size_t>(offset) / kOffsetStep;
    if (fd != kFd || i >= buffers_.size() || static_cast<std::size_t>(offset) % kOffsetStep || length != buffers_[i].memory.size())
      return errno = EINVAL, MAP_FAILED;
    ++mapped;
    return buffers_[i].memory.data();
  }
  int munmap(void* address, std::size_t) override {
    calls.push_back("munmap");
    --mapped;
    return address ? 0 : -1;
  }
  int poll(pollfd* fds, nfds_t, int) override {
    fds[0].revents = 0;
    if (pollError) fds[0].revents |= POLLERR;
    if (!done_.empty()) fds[0].revents |= POLLIN;
    return fds[0].revents ? 1 : 0;
  }
  int ioctl(int fd, unsigned long request, void* arg) override {
    if (fd != kFd || !fdOpen) return errno = EBADF, -1;
    switch (request) {
      case VIDIOC_QUERYCAP: {
        calls.push_back("QUERYCAP");
        auto* cap = static_cast<v4l2_capability*>(arg);
        std::snprintf(reinterpret_cast<char*>(cap->driver), sizeof cap->driver, "fake-ov5640");
        cap->capabilities = V4L2_CAP_VIDEO_CAPTURE | V4L2_CAP_STREAMING | V4L2_CAP_DEVICE_CAPS;
        cap->device_caps = V4L2_CAP_VIDEO_CAPTURE | V4L2_CAP_STREAMING;
        return 0;
      }
      case VIDIOC_S_FMT: {
        calls.push_back("S_FMT");
        auto* f = static_cast<v4l2_format*>(arg);
        if (f->type != V4L2_BUF_TYPE_VIDEO_CAPTURE || streaming) return errno = EINVAL, -1;
        requested_ = f->fmt.pix;
        // Like a driver: the closest size it can do and its own pixel format if it lacks the one asked for.
        width_ = std::min(f->fmt.pix.width, maxWidth);
        height_ = std::min(f->fmt.pix.height, maxHeight);
        f->fmt.pix.width = width_;
        f->fmt.pix.height = height_;
        f->fmt.pix.pixelformat = pixelFormat;
        f->fmt.pix.bytesperline = stride();
        f->fmt.pix.sizeimage = stride() * height_;
        return 0;
      }
      case VIDIOC_S_PARM: {
        calls.push_back("S_PARM");
        auto* p = static_cast<v4l2_streamparm*>(arg);
        timePerFrame = p->parm.capture.timeperframe;
        p->parm.capture.capability = V4L2_CAP_TIMEPERFRAME;
        return 0;
      }
      case VIDIOC_REQBUFS: {
        calls.push_back("REQBUFS");
        auto* r = static_cast<v4l2_requestbuffers*>(arg);
        if (r->memory != V4L2_MEMORY_MMAP || streaming) return errno = EINVAL, -1;
        if (r->count > 0 && mapped) return errno = EBUSY, -1;  // old mappings still alive
        r->count = std::min(r->count, maxBuffers);
        buffers_.assign(r->count, Buffer{});
        for (auto& b : buffers_) b.memory.assign(stride() * height_, 0);
        queued_.clear();
        done_.clear();
        return 0;
      }
      case VIDIOC_QUERYBUF: {
        calls.push_back("QUERYBUF");
        auto* b = static_cast<v4l2_buffer*>(arg);
        if (b->index >= buffers_.size()) return errno = EINVAL, -1;
        b->length = static_cast<std::uint32_t>(buffers_[b->index].memory.size());
        b->m.offset = b->index * kOffsetStep;
        return 0;
      }
      case VIDIOC_QBUF: {
        calls.push_back("QBUF");
        auto* b = static_cast<v4l2_buffer*>(arg);
        if (b->index >= buffers_.size()) return errno = EINVAL, -1;
        for (auto q : queued_)
          if (q == b->index) return errno = EINVAL, -1;  // queued twice
        queued_.push_back(b->index);
        return 0;
      }
      case VIDIOC_DQBUF: {
        calls.push_back("DQBUF");
        if (dqbufErrno) {
          errno = dqbufErrno;
          dqbufErrno = 0;
          return -1;
        }
        if (done_.empty()) return errno = EAGAIN, -1;
        auto* b = static_cast<v4l2_buffer*>(arg);
        const std::uint32_t i = done_.front();
        done_.pop_front();
        b->index = i;
        b->bytesused = buffers_[i].bytesused;
        b->flags = buffers_[i].flags;
        b->timestamp = buffers_[i].timestamp;
        b->length = static_cast<std::uint32_t>(buffers_[i].memory.size());
        return 0;
      }
      case VIDIOC_STREAMON:
        calls.push_back("STREAMON");
        if (queued_.empty()) return errno = EINVAL, -1;
        streaming = true;
        return 0;
      case VIDIOC_STREAMOFF:
        calls.push_back("STREAMOFF");
        streaming = false;
        queued_.clear();
        done_.clear();
        return 0;
      case VIDIOC_QUERYCTRL: {
        auto* q = static_cast<v4l2_queryctrl*>(arg);
        const bool flip = q->id == V4L2_CID_HFLIP || q->id == V4L2_CID_VFLIP;
        auto it = controls.find(q->id);
        if (it == controls.end() || (flip && !flipControls)) return errno = EINVAL, -1;
        q->minimum = it->second.min;
        q->maximum = it->second.max;
        q->step = it->second.step;
        return 0;
      }
      case VIDIOC_S_CTRL: {
        auto* c = static_cast<v4l2_control*>(arg);
        auto it = controls.find(c->id);
        if (it == controls.end() || c->value < it->second.min || c->value > it->second.max) return errno = ERANGE, -1;
        it->second.value = c->value;
        setControls.emplace_back(c->id, c->value);
        calls.push_back("S_CTRL");
        return 0;
      }
      case VIDIOC_G_CTRL: {
        auto* c = static_cast<v4l2_control*>(arg);
        auto it = controls.find(c->id);
        if (it == controls.end()) return errno = EINVAL, -1;
        c->value = it->second.value;
        return 0;
      }
      case UVCIOC_CTRL_QUERY: {
        auto* q = static_cast<uvc_xu_control_query*>(arg);
        if (!naoExtensionUnit) return errno = ENOENT, -1;  // uvcvideo: no such unit
        if (q->unit != 3 || q->selector != 9 || q->query != UVC_SET_CUR || q->size != 17) return errno = EINVAL, -1;
        exposureWeightWrites.emplace_back(q->data, q->data + q->size);
        calls.push_back("XU_SET_CUR");
        return 0;
      }
    }
    return errno = ENOTTY, -1;
  }
  v4l2_pix_format requested_{};

 private:
  static constexpr int kFd = 42;
  static constexpr std::size_t kOffsetStep = 1 << 24;
  struct Buffer {
    std::vector<std::uint8_t> memory;
    std::uint32_t bytesused = 0, flags = 0;
    timeval timestamp{};
  };
  std::vector<Buffer> buffers_;
  std::deque<std::uint32_t> queued_, done_;
  std::uint32_t width_ = 0, height_ = 0;
};

struct V4l2 : ::testing::Test {
  std::shared_ptr<FakeDriver> driver = std::make_shared<FakeDriver>();
  std::vector<std::string> log;
  V4l2CameraConfig config;
  std::unique_ptr<V4l2Camera> camera;
  void make() {
    camera = std::make_unique<V4l2Camera>(driver, config, [this](const std::string& l) { log.push_back(l); });
  }
  bool logged(const std::string& text) const {
    for (const auto& l : log)
      if (l.find(text) != std::string::npos) return true;
    return false;
  }
  std::uint8_t expected(std::uint8_t seed, int row, int byte) const {
    return static_cast<std::uint8_t>(seed + row * 3 + byte);
  }
};

TEST_F(V4l2, NegotiatesYuyvAt30HzWithMmapBuffers) {
  make();
  ASSERT_TRUE(camera->open(0.0)) << camera->lastError();
  EXPECT_EQ(driver->requested_.pixelformat, static_cast<std::uint32_t>(V4L2_PIX_FMT_YUYV));
  EXPECT_EQ(driver->requested_.width, 640u);
  EXPECT_EQ(driver->requested_.height, 480u);
  EXPECT_EQ(driver->requested_.field, static_cast<std::uint32_t>(V4L2_FIELD_NONE));
  EXPECT_EQ(driver->timePerFrame.numerator, 1u);
  EXPECT_EQ(driver->timePerFrame.denominator, 30u);
  EXPECT_EQ(driver->mapped, 4);
  EXPECT_EQ(driver->queued(), 4u);
  EXPECT_TRUE(driver->streaming);
  // The order a V4L2 capture needs.
  const std::vector<std::string> start(driver->calls.begin(), driver->calls.begin() + 18);
  EXPECT_EQ(start, (std::vector<std::string>{"open", "QUERYCAP", "S_FMT", "S_PARM", "REQBUFS", "QUERYBUF", "mmap", "QBUF",
                                            "QUERYBUF", "mmap", "QBUF", "QUERYBUF", "mmap", "QBUF", "QUERYBUF", "mmap",
                                            "QBUF", "STREAMON"}));
  EXPECT_EQ(camera->width(), 640);
  EXPECT_EQ(camera->height(), 480);
  EXPECT_TRUE(logged("streaming 640x480 YUYV at 30 Hz, 4 mmap buffers"));
}

TEST_F(V4l2, TakesTheDriversSizeAndRefusesOtherFormats) {
  driver->maxWidth = 320;
  driver->maxHeight = 240;
  make();
  ASSERT_TRUE(camera->open(0));
  EXPECT_EQ(camera->width(), 320);
  EXPECT_TRUE(logged("asked for 640x480, the driver delivers 320x240"));
  camera.reset();
  log.clear();
  driver->pixelFormat = V4L2_PIX_FMT_MJPEG;
  make();
  EXPECT_FALSE(camera->open(0));
  EXPECT_EQ(camera->lastError(), "the driver offers MJPG instead of YUYV");
  EXPECT_TRUE(logged("camera top (/dev/video-top): the driver offers MJPG instead of YUYV"));
  EXPECT_EQ(driver->fdOpen, 0);
  EXPECT_EQ(driver->mapped, 0);
}

TEST_F(V4l2, NeedsTwoBuffers) {
  driver->maxBuffers = 1;
  make();
  EXPECT_FALSE(camera->open(0));
  EXPECT_EQ(camera->lastError(), "the driver gives only 1 buffer(s), 2 are needed");
  EXPECT_EQ(driver->fdOpen, 0);
}

TEST_F(V4l2, DeliversTheNewestFrameAndRequeuesEveryBuffer) {
  make();
  ASSERT_TRUE(camera->open(100.0));
  CameraImage img;
  EXPECT_FALSE(camera->grab(img, 100.01));  // nothing captured yet
  ASSERT_TRUE(driver->capture(7, 100.020));
  ASSERT_TRUE(camera->grab(img, 100.03));
  EXPECT_EQ(img.camera, CameraId::Top);
  ASSERT_TRUE(img.valid());
  EXPECT_EQ(img.width, 640);
  EXPECT_NEAR(img.timestamp, 100.020, 1e-6);  // the kernel's capture time
  EXPECT_EQ(img.yuyv[0], expected(7, 0, 0));
  EXPECT_EQ(img.yuyv[(10 * 640 + 3) * 2 + 1], expected(7, 10, 7));
  EXPECT_EQ(driver->queued(), 4u);  // handed back at once
  EXPECT_FALSE(camera->grab(img, 100.04));
  // Three frames while the program was busy: the newest one, the others dropped and requeued.
  ASSERT_TRUE(driver->capture(1, 100.05));
  ASSERT_TRUE(driver->capture(2, 100.083));
  ASSERT_TRUE(driver->capture(3, 100.117));
  ASSERT_TRUE(camera->grab(img, 100.12));
  EXPECT_EQ(img.yuyv[0], expected(3, 0, 0));
  EXPECT_NEAR(img.timestamp, 100.117, 1e-6);
  EXPECT_EQ(camera->stats().dropped, 2u);
  EXPECT_EQ(camera->stats().frames, 2u);
  EXPECT_EQ(driver->queued(), 4u);
}

TEST_F(V4l2, CopiesRowsPastTheDriversPadding) {
  driver->padding = 64;
  config.width = 320;
  config.height = 240;
  config.camera = CameraId::Bottom;
  make();
  ASSERT_TRUE(camera->open(0));
  ASSERT_TRUE(driver->capture(9, 0.5));
  CameraImage img;
  ASSERT_TRUE(camera->grab(img, 0.5));
  ASSERT_TRUE(img.valid());
  EXPECT_EQ(img.camera, CameraId::Bottom);
  for (int row : {0, 1, 239})
    for (int byte : {0, 1, 639}) EXPECT_EQ(img.yuyv[static_cast<std::size_t>(row) * 640 + byte], expected(9, row, byte));
}

TEST_F(V4l2, RotatesTheUpsideDownTopCamera) {
  config.rotate180 = true;
  make();
  ASSERT_TRUE(camera->open(0));
  EXPECT_FALSE(camera->softwareRotation());  // the driver flips
  EXPECT_EQ(driver->controlValue(V4L2_CID_HFLIP), 1);
  EXPECT_EQ(driver->controlValue(V4L2_CID_VFLIP), 1);
  camera.reset();
  driver->flipControls = false;
  driver->controls[V4L2_CID_HFLIP].value = driver->controls[V4L2_CID_VFLIP].value = 0;
  make();
  ASSERT_TRUE(camera->open(0));
  EXPECT_TRUE(camera->softwareRotation());
  ASSERT_TRUE(driver->capture(0, 1));
  CameraImage img;
  ASSERT_TRUE(camera->grab(img, 1));
  // Pixel (x, y) is the sensor's (W-1-x, H-1-y): the luma of the last pixel comes first, the
  // chroma of its pair stays with it.
  const std::size_t last = (static_cast<std::size_t>(479) * 640 + 638) * 2;
  EXPECT_EQ(img.yuyv[0], expected(0, 479, 1278));  // Y1 of the last pair
  EXPECT_EQ(img.yuyv[1], expected(0, 479, 1277 - 0));  // U of the last pair
  EXPECT_EQ(img.yuyv[2], expected(0, 479, 1276));  // Y0 of the last pair
  EXPECT_EQ(img.yuyv[3], expected(0, 479, 1279));  // V of the last pair
  EXPECT_EQ(img.yuyv[last + 0], expected(0, 0, 2));
  EXPECT_EQ(img.yuyv[last + 2], expected(0, 0, 0));
}

TEST_F(V4l2, SetsExposureGainAndWhiteBalanceWithinTheDriversRanges) {
  config.controls.autoExposure = false;
  config.controls.exposure = 5000;  // beyond the driver's 2500
  config.controls.gain = 100;
  config.controls.autoWhiteBalance = false;
  config.controls.whiteBalance = 4321;  // step 100
  make();
  ASSERT_TRUE(camera->open(0));
  EXPECT_EQ(driver->controlValue(V4L2_CID_EXPOSURE_AUTO), V4L2_EXPOSURE_MANUAL);
  EXPECT_EQ(driver->controlValue(V4L2_CID_EXPOSURE_ABSOLUTE), 2500);
  EXPECT_EQ(driver->controlValue(V4L2_CID_GAIN), 100);
  EXPECT_EQ(driver->controlValue(V4L2_CID_AUTO_WHITE_BALANCE), 0);
  EXPECT_EQ(driver->controlValue(V4L2_CID_WHITE_BALANCE_TEMPERATURE), 4300);
  EXPECT_TRUE(logged("exposure 5000 is outside the driver's range, using 2500"));
  // Automatic modes go off before their manual values are set.
  auto order = [&](std::uint32_t id) {
    for (std::size_t i = 0; i < driver->setControls.size(); ++i)
      if (driver->setControls[i].first == id) return static_cast<int>(i);
    return -1;
  };
  EXPECT_LT(order(V4L2_CID_EXPOSURE_AUTO), order(V4L2_CID_EXPOSURE_ABSOLUTE));
  EXPECT_LT(order(V4L2_CID_AUTO_WHITE_BALANCE), order(V4L2_CID_WHITE_BALANCE_TEMPERATURE));
  camera.reset();
  driver->controls.erase(V4L2_CID_GAIN);
  make();
  ASSERT_TRUE(camera->open(0));  // a missing control is logged, not fatal
  EXPECT_TRUE(logged("the driver has no gain control"));
}

TEST_F(V4l2, RecoversFromADeviceError) {
  make();
  ASSERT_TRUE(camera->open(0));
  driver->dqbufErrno = EIO;
  ASSERT_TRUE(driver->capture(1, 0.03));
  CameraImage img;
  EXPECT_FALSE(camera->grab(img, 0.04));
  EXPECT_TRUE(logged("camera top (/dev/video-top): VIDIOC_DQBUF: Input/output error; reopening"));
  EXPECT_EQ(camera->stats().errors, 1u);
  EXPECT_EQ(camera->stats().reopens, 1u);
  EXPECT_TRUE(camera->streaming());
  EXPECT_EQ(driver->opens, 2);
  EXPECT_EQ(driver->mapped, 4);  // the old mappings went, new ones came
  ASSERT_TRUE(driver->capture(2, 0.07));
  ASSERT_TRUE(camera->grab(img, 0.08));
  EXPECT_EQ(img.yuyv[0], expected(2, 0, 0));
}

TEST_F(V4l2, RetriesAVanishedDeviceUntilItIsBack) {
  make();
  ASSERT_TRUE(camera->open(0));
  driver->pollError = true;
  driver->openErrno = ENODEV;
  CameraImage img;
  EXPECT_FALSE(camera->grab(img, 1.0));  // error, reopen fails
  EXPECT_FALSE(camera->streaming());
  EXPECT_TRUE(logged("the device reported an error"));
  EXPECT_TRUE(logged("open: No such device"));
  const int opens = driver->opens;
  EXPECT_FALSE(camera->grab(img, 1.5));  // not before reopenInterval
  EXPECT_EQ(driver->opens, opens);
  EXPECT_FALSE(camera->grab(img, 2.1));  // tried again, still gone
  EXPECT_EQ(driver->opens, opens + 1);
  driver->openErrno = 0;
  driver->pollError = false;
  EXPECT_FALSE(camera->grab(img, 3.2));  // back
  EXPECT_TRUE(camera->streaming());
  ASSERT_TRUE(driver->capture(5, 3.22));
  EXPECT_TRUE(camera->grab(img, 3.23));
}

TEST_F(V4l2, ReopensWhenFramesStop) {
  make();
  ASSERT_TRUE(camera->open(0));
  CameraImage img;
  EXPECT_FALSE(camera->grab(img, 0.5));
  EXPECT_EQ(driver->opens, 1);
  EXPECT_FALSE(camera->grab(img, 1.2));  // > frameTimeout without a frame
  EXPECT_TRUE(logged("no frame for 1200 ms; reopening"));
  EXPECT_EQ(driver->opens, 2);
  EXPECT_TRUE(camera->streaming());
}

TEST_F(V4l2, DropsDamagedFrames) {
  make();
  ASSERT_TRUE(camera->open(0));
  CameraImage img;
  ASSERT_TRUE(driver->capture(1, 0.03, V4L2_BUF_FLAG_ERROR));
  EXPECT_FALSE(camera->grab(img, 0.04));
  ASSERT_TRUE(driver->capture(1, 0.06, 0, 1000));  // short
  EXPECT_FALSE(camera->grab(img, 0.07));
  EXPECT_EQ(camera->stats().dropped, 2u);
  EXPECT_EQ(driver->queued(), 4u);
  ASSERT_TRUE(driver->capture(4, 0.1));
  EXPECT_TRUE(camera->grab(img, 0.1));
}

// The robot program's auto exposure weights reach the NAO camera's extension unit: window the
// whole image, 16 weights two to a byte, row-major, even cell low; written again after a
// reopen; a camera without the unit is logged once and left alone.
TEST(NaoExposureWeights, PayloadHoldsTheWindowAndTheCellsTwoToAByte) {
  ExposureWeights w;
  for (int k = 0; k < 16; ++k) w.cell[static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(k);
  const auto p = naoExposureWeightsPayload(w, 640, 480);
  const std::array<std::uint8_t, 17> expected{1,    0,    0,    0,    0,    0x02, 0x80, 0x01, 0xe0,
                                              0x10, 0x32, 0x54, 0x76, 0x98, 0xba, 0xdc, 0xfe};
  EXPECT_EQ(p, expected);
  w.cell.fill(200);  // out of range: the most a cell can weigh
  EXPECT_EQ(naoExposureWeightsPayload(w, 320, 240)[9], 0xff);
  EXPECT_EQ(naoExposureWeightsPayload(w, 320, 240)[6], 0x40);
}

TEST_F(V4l2, WritesTheAutoExposureWeightsAndAgainAfterAReopen) {
  make();
  ASSERT_TRUE(camera->open(0));
  EXPECT_TRUE(driver->exposureWeightWrites.empty()) << "the camera's own metering until the program chooses";
  ExposureWeights w;
  w.cell.fill(0);
  w.cell[12] = w.cell[13] = w.cell[14] = w.cell[15] = 15;  // the bottom row only
  camera->setExposureWeights(w);
  ASSERT_EQ(driver->exposureWeightWrites.size(), 1u);
  const std::vector<std::uint8_t> expected{1, 0, 0, 0, 0, 0x02, 0x80, 0x01, 0xe0, 0, 0, 0, 0, 0, 0, 0xff, 0xff};
  EXPECT_EQ(driver->exposureWeightWrites[0], expected);
  camera->setExposureWeights(w);  // unchanged: nothing written
  EXPECT_EQ(driver->exposureWeightWrites.size(), 1u);
  driver->dqbufErrno = EIO;
  ASSERT_TRUE(driver->capture(1, 0.03));
  CameraImage img;
  EXPECT_FALSE(camera->grab(img, 0.04));  // reopens
  ASSERT_EQ(driver->exposureWeightWrites.size(), 2u);
  EXPECT_EQ(driver->exposureWeightWrites[1], expected);
}

TEST_F(V4l2, ACameraWithoutTheNaoExtensionUnitKeepsItsOwnMetering) {
  driver->naoExtensionUnit = false;
  make();
  ASSERT_TRUE(camera->open(0));
  ExposureWeights w;
  w.cell.fill(3);
  camera->setExposureWeights(w);
  w.cell.fill(4);
  camera->setExposureWeights(w);
  int lines = 0;
  for (const auto& l : log) lines += l.find("setting the auto exposure weights failed") != std::string::npos;
  EXPECT_EQ(lines, 1);
  EXPECT_TRUE(logged("camera top (/dev/video-top): setting the auto exposure weights failed"));
  CameraImage img;
  ASSERT_TRUE(driver->capture(1, 0.03));
  EXPECT_TRUE(camera->grab(img, 0.04));  // and it streams on
}

TEST_F(V4l2, ClosesCleanly) {
  make();
  ASSERT_TRUE(camera->open(0));
  camera.reset();
  EXPECT_EQ(driver->fdOpen, 0);
  EXPECT_EQ(driver->mapped, 0);
  EXPECT_FALSE(driver->streaming);
  const auto& c = driver->calls;
  EXPECT_NE(std::find(c.begin(), c.end(), "STREAMOFF"), c.end());
}

TEST_F(V4l2, WithoutAKernelTimestampTheFrameIsStampedWhenTaken) {
  driver->timestampClock = V4L2_BUF_FLAG_TIMESTAMP_UNKNOWN;
  make();
  ASSERT_TRUE(camera->open(50.0));
  ASSERT_TRUE(driver->capture(1, 3.0));  // a driver's own clock, unrelated to CLOCK_MONOTONIC
  CameraImage img;
  ASSERT_TRUE(camera->grab(img, 50.2));
  EXPECT_DOUBLE_EQ(img.timestamp, 50.2);
}

// Two fake drivers behind one V4l2Device, told apart by path (the NAO's two cameras), each
// with its own descriptor.
class TwoCameras : public V4l2Device {
 public:
  std::shared_ptr<FakeDriver> top = std::make_shared<FakeDriver>(), bottom = std::make_shared<FakeDriver>();
  TwoCameras() { bottom->path = "/dev/video-bottom"; }
  int open(const std::string& path, int flags) override {
    FakeDriver& d = path == bottom->path ? *bottom : *top;
    const int fd = d.open(path, flags);
    return fd < 0 ? fd : fd + (&d == bottom.get() ? kBottom : 0);
  }
  int close(int fd) override { return of(fd).close(raw(fd)); }
  int ioctl(int fd, unsigned long request, void* arg) override { return of(fd).ioctl(raw(fd), request, arg); }
  void* mmap(std::size_t length, int fd, off_t offset) override { return of(fd).mmap(length, raw(fd), offset); }
  int munmap(void* address, std::size_t length) override {
    // Each driver's buffers are its own memory: ask the one that owns it.
    return (top->owns(address) ? *top : *bottom).munmap(address, length);
  }
  int poll(pollfd* fds, nfds_t count, int timeoutMs) override {
    pollfd p = fds[0];
    p.fd = raw(p.fd);
    const int n = of(fds[0].fd).poll(&p, count, timeoutMs);
    fds[0].revents = p.revents;
    return n;
  }

 private:
  static constexpr int kBottom = 1000;
  FakeDriver& of(int fd) { return fd >= kBottom ? *bottom : *top; }
  static int raw(int fd) { return fd >= kBottom ? fd - kBottom : fd; }
};

double monotonicNow() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<double>(ts.tv_sec) + ts.tv_nsec * 1e-9;
}

// The backend's camera path (`--cameras v4l2`): both devices opened with the documented
// settings, the top image turned upright, kernel timestamps moved onto the backend clock that
// the sensor frames use. LoLA is a listening Unix socket here (the backend only connects).
TEST(NaoBackendCameras, DeliverBothCamerasOnTheBackendClock) {
  char dir[] = "/tmp/v4l2_test.XXXXXX";
  ASSERT_NE(mkdtemp(dir), nullptr);
  const std::string socketPath = std::string(dir) + "/lola.sock";
  const int listener = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::snprintf(addr.sun_path, sizeof addr.sun_path, "%s", socketPath.c_str());
  ASSERT_EQ(::bind(listener, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  ASSERT_EQ(::listen(listener, 1), 0);

  auto cams = std::make_shared<TwoCameras>();
  NaoBackendConfig config;
  config.lolaSocket = socketPath;
  config.connectTimeout = 2;
  config.v4l2 = cams;
  std::vector<std::string> log;
  {
    NaoBackend backend(config, [&](const std::string& l) { log.push_back(l); });
    // The documented settings: top 640x480 flipped by the driver, bottom 320x240, 30 Hz.
    EXPECT_EQ(cams->top->requested_.width, 640u);
    EXPECT_EQ(cams->top->requested_.height, 480u);
    EXPECT_EQ(cams->bottom->requested_.width, 320u);
    EXPECT_EQ(cams->bottom->requested_.height, 240u);
    EXPECT_EQ(cams->top->timePerFrame.denominator, 30u);
    EXPECT_EQ(cams->bottom->timePerFrame.denominator, 30u);
    EXPECT_EQ(cams->top->controlValue(V4L2_CID_VFLIP), 1);
    EXPECT_EQ(cams->bottom->controlValue(V4L2_CID_VFLIP), 0);

    CameraImage img;
    EXPECT_FALSE(backend.takeImage(CameraId::Top, img));  // nothing captured yet
    // Exposures taken 40 ms and 5 ms before now, by the kernel's CLOCK_MONOTONIC. The backend
    // clock's offset lies between the two readings around it.
    const double before = backend.now();
    const double now = monotonicNow();
    const double after = backend.now();
    ASSERT_TRUE(cams->top->capture(11, now - 0.040));
    ASSERT_TRUE(cams->bottom->capture(22, now - 0.005));
    ASSERT_TRUE(backend.takeImage(CameraId::Top, img));
    EXPECT_EQ(img.camera, CameraId::Top);
    EXPECT_EQ(img.width, 640);
    EXPECT_EQ(img.yuyv[0], static_cast<std::uint8_t>(11));
    const double us = 1e-6;  // V4L2 stamps in microseconds
    EXPECT_GE(img.timestamp, before - 0.040 - us);
    EXPECT_LE(img.timestamp, after - 0.040 + us);
    ASSERT_TRUE(backend.takeImage(CameraId::Bottom, img));
    EXPECT_EQ(img.camera, CameraId::Bottom);
    EXPECT_EQ(img.width, 320);
    EXPECT_EQ(img.yuyv[0], static_cast<std::uint8_t>(22));
    EXPECT_GE(img.timestamp, before - 0.005 - us);
    EXPECT_LE(img.timestamp, after - 0.005 + us);
    EXPECT_FALSE(backend.takeImage(CameraId::Bottom, img));  // each frame once
  }
  // The backend's end closes both cameras.
  EXPECT_EQ(cams->top->fdOpen, 0);
  EXPECT_EQ(cams->bottom->fdOpen, 0);
  EXPECT_EQ(cams->top->mapped + cams->bottom->mapped, 0);

  // A camera that is not there does not stop the backend: the other one streams.
  cams = std::make_shared<TwoCameras>();
  cams->bottom->openErrno = ENODEV;
  config.v4l2 = cams;
  log.clear();
  {
    NaoBackend backend(config, [&](const std::string& l) { log.push_back(l); });
    bool named = false;
    for (const auto& l : log) named |= l.find("camera bottom (/dev/video-bottom): open: No such device") != std::string::npos;
    EXPECT_TRUE(named);
    ASSERT_TRUE(cams->top->capture(3, monotonicNow()));
    CameraImage img;
    EXPECT_TRUE(backend.takeImage(CameraId::Top, img));
    EXPECT_FALSE(backend.takeImage(CameraId::Bottom, img));
  }
  ::close(listener);
  ::unlink(socketPath.c_str());
  ::rmdir(dir);
}

TEST(V4l2Kernel, MissingDeviceIsReportedNotFatal) {
  V4l2CameraConfig config;
  config.device = "/dev/video-does-not-exist";
  std::vector<std::string> log;
  V4l2Camera camera(kernelV4l2Device(), config, [&](const std::string& l) { log.push_back(l); });
  EXPECT_FALSE(camera.open(0));
  EXPECT_EQ(camera.lastError(), "open: No such file or directory");
  CameraImage img;
  EXPECT_FALSE(camera.grab(img, 0.5));
  ASSERT_EQ(log.size(), 1u);  // the same error is not repeated every retry
}

}  // namespace
}  // namespace nao
