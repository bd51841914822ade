#pragma once
// A camera made of image files (--cameras files:DIR): the PNG and JPEG files of one folder in
// name order, looping, one frame per period, to replay a recording or to run the NAO backend's
// cognition without a camera. Frames are decoded ahead in a thread of the camera's own, so
// grab() only swaps a ready buffer out, as V4l2Camera's grab() copies a dequeued one: a slow
// decode never holds up the motion cycle that takes the image; each file is decoded once while
// the frames fit a cache of FileCamera::kCacheBytes. The files: imageFilesIn
// (robot/nao/ImageFiles.h).
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "robot/Backend.h"
#include "robot/nao/CameraSource.h"

namespace nao {

class FileCamera : public CameraSource {
 public:
  // Reads an image file (throws nao::Error naming it when it cannot); the robot program's
  // image decoding lives outside robot/ (sim::readImage in nao-soccer).
  using Decoder = std::function<CameraImage(const std::string& path, CameraId camera)>;
  using Log = std::function<void(const std::string&)>;

  // The first frame is due at `start` (on the clock grab's `now` is given in), then one every
  // period. waitForDecode (--lockstep): grab waits for a due frame's decoding instead of
  // leaving it to a later cycle, and frames stay on their schedule, so that a replay hands the
  // same frames to the same cycles whatever the machine's speed.
  FileCamera(CameraId camera, std::vector<std::string> files, Decoder decode, double start,
             double period = kCameraPeriod, Log log = {}, bool waitForDecode = false);
  ~FileCamera() override;
  FileCamera(const FileCamera&) = delete;
  FileCamera& operator=(const FileCamera&) = delete;

  // Decoded frames kept for the next round of the loop (a 640x480 frame is 600 KB).
  static constexpr std::size_t kCacheBytes = 256u << 20;

  // A frame when one is due and decoded; its timestamp is the time it was due.
  bool grab(CameraImage& image, double now) override;

 private:
  void decodeLoop();

  CameraId camera_;
  std::vector<std::string> files_;
  Decoder decode_;
  double period_, due_;
  Log log_;
  bool waitForDecode_;
  std::mutex mutex_;  // ready_, next_, stop_, exhausted_
  std::condition_variable wake_, decoded_;
  bool ready_ = false, stop_ = false, exhausted_ = false;
  CameraImage next_;
  std::thread thread_;
};

}  // namespace nao
