#include "robot/nao/FileCamera.h"

#include <algorithm>
#include <utility>

namespace nao {

FileCamera::FileCamera(CameraId camera, std::vector<std::string> files, Decoder decode, double start, double period,
                       Log log, bool waitForDecode)
    : camera_(camera), files_(std::move(files)), decode_(std::move(decode)), period_(period), due_(start),
      log_(std::move(log)), waitForDecode_(waitForDecode) {
  if (!files_.empty()) thread_ = std::thread([this] { decodeLoop(); });
}

FileCamera::~FileCamera() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_one();
  if (thread_.joinable()) thread_.join();
}

void FileCamera::decodeLoop() {
  std::size_t index = 0, brokenCount = 0;
  std::vector<bool> broken(files_.size(), false);  // logged once, then left out
  // A folder replays in a loop: each file is decoded once while the frames fit kCacheBytes, so
  // a replay costs no decoding CPU beside the program after the first round.
  std::vector<CameraImage> cache(files_.size());
  std::size_t cachedBytes = 0;
  CameraImage image;
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stop_ || !ready_; });
      if (stop_) return;
    }
    const std::size_t i = index;
    index = (index + 1) % files_.size();
    if (broken[i]) continue;
    try {
      if (cache[i].valid()) {
        image = cache[i];
      } else {
        image = decode_(files_[i], camera_);
        image.camera = camera_;
        if (image.valid() && cachedBytes + image.yuyv.size() <= kCacheBytes) {
          cachedBytes += image.yuyv.size();
          cache[i] = image;
        }
      }
    } catch (const std::exception& e) {
      broken[i] = true;
      if (log_) log_(std::string("camera ") + cameraName(camera_) + ": skipped " + e.what());
      if (++brokenCount == files_.size()) {  // nothing left to show
        std::lock_guard<std::mutex> lock(mutex_);
        exhausted_ = true;
        decoded_.notify_all();
        return;
      }
      continue;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    std::swap(next_, image);
    ready_ = true;
    decoded_.notify_all();
  }
}

bool FileCamera::grab(CameraImage& image, double now) {
  if (now < due_ || files_.empty()) return false;
  {
    std::unique_lock<std::mutex> lock(mutex_, std::defer_lock);
    if (waitForDecode_) {
      lock.lock();
      decoded_.wait(lock, [this] { return ready_ || exhausted_; });
    } else {
      lock.try_lock();
    }
    if (!lock.owns_lock() || !ready_) return false;  // not decoded yet: the next cycle
    std::swap(image, next_);
    ready_ = false;
  }
  wake_.notify_one();
  image.timestamp = due_;
  // After a stall (a busy machine) the next frame is due a period from now, not in a burst;
  // in lockstep the schedule is kept (the clock is the LoLA packets').
  due_ = waitForDecode_ ? due_ + period_ : std::max(due_ + period_, now + period_ * 0.5);
  return true;
}

}  // namespace nao
