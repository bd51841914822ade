#pragma once
// A camera whose frames come over a Unix socket (--cameras socket:PATH): what a simulator
// standing in for the NAO (tests/sim_lola_peer.cpp) renders, handed to cognition the way the
// V4L2 cameras hand theirs: a thread of the camera's own receives, grab() only swaps a ready
// frame out, so a slow peer never holds up the motion cycle.
//
// The wire, both cameras on one listening socket, one connection each:
//   camera -> peer, once:      "NAOCAM1" and one byte, the camera (0 top, 1 bottom);
//   peer -> camera, per frame: "NAOF", u32 width, u32 height, u32 0, f64 capture time on the
//                              program's clock (CLOCK_MONOTONIC s; with --clock lola, 12 ms per
//                              LoLA packet), all host byte order, then width*height*2 bytes
//                              of YUYV;
//   camera -> peer, any time:  "NAOW" and the 16 auto exposure weights (robot/ExposureWeights.h,
//                              row-major), when the program changes them and after a reconnect.
// A frame that breaks this (bad magic, an odd or huge size, a time that is not finite) is
// named in one log line and the connection is dropped and made again.
#include <atomic>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "robot/nao/CameraSource.h"

namespace nao {

inline constexpr char kSocketCameraHello[8] = {'N', 'A', 'O', 'C', 'A', 'M', '1', 0};  // last: the camera
inline constexpr char kSocketFrameMagic[4] = {'N', 'A', 'O', 'F'};
inline constexpr char kSocketWeightsMagic[4] = {'N', 'A', 'O', 'W'};
inline constexpr std::size_t kSocketWeightsSize = 20;
inline constexpr std::size_t kSocketFrameHeaderSize = 24;
inline constexpr int kSocketFrameMaxSide = 4096;

class SocketCamera : public CameraSource {
 public:
  using Log = std::function<void(const std::string&)>;

  SocketCamera(CameraId camera, std::string path, Log log = {});
  ~SocketCamera() override;
  SocketCamera(const SocketCamera&) = delete;
  SocketCamera& operator=(const SocketCamera&) = delete;

  // The newest frame received since the last call; its timestamp is the peer's capture time.
  bool grab(CameraImage& image, double now) override;
  // Sent to the peer (which renders with them), never blocking: a full socket drops them.
  void setExposureWeights(const ExposureWeights& weights) override;

  long received() const;  // frames received
  long rejected() const;  // connections dropped for a broken frame

 private:
  void receiveLoop();
  int connectOnce();                             // a connected socket that said hello, or -1
  bool readExactly(int fd, void* data, std::size_t size);  // false: closed, error or stop
  void sendWeights(int fd);                                // with sendMutex_ held

  CameraId camera_;
  std::string path_;
  Log log_;
  mutable std::mutex mutex_;  // ready_, next_, received_, rejected_
  bool ready_ = false;
  CameraImage next_;
  long received_ = 0, rejected_ = 0;
  std::mutex sendMutex_;  // connection_, weights_
  int connection_ = -1;   // the receiver's connected socket, -1 between connections
  std::optional<ExposureWeights> weights_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace nao
