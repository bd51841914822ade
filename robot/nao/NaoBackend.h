#pragma once
// The robot program's hardware on a real NAO V6: LoLA's Unix socket for the joints and
// sensors (one msgpack map in, one out, every 12 ms) and the two V4L2 cameras. Safety sits
// between the program's request and the motors (robot/nao/Safety.h). SIGINT and SIGTERM
// end the run softly once installSignalHandlers() was called.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "robot/Backend.h"
#include "robot/nao/CameraSource.h"
#include "robot/nao/LolaClient.h"
#include "robot/nao/LolaPacket.h"
#include "robot/nao/Safety.h"
#include "robot/nao/V4l2Camera.h"

namespace nao {

struct NaoBackendConfig {
  std::string lolaSocket = "/tmp/robocup";
  double connectTimeout = 20;  // s to wait for LoLA's socket at start
  int staleCycles = 4;         // no sensor packet for this many cycles: soft
  int stopCycles = 3;          // soft answers after a stop request before the run ends
  // The program's clock: false, CLOCK_MONOTONIC (as on a NAO: physics runs in real time); true,
  // 12 ms per LoLA packet, for a simulated NAO slower than real time, whose camera frames then
  // carry that clock too. LoLA's safety (stale packets, answer times) stays on the real clock.
  bool lolaClock = false;
  Safety::Params safety;
  bool cameras = true;
  std::array<V4l2CameraConfig, kNumCameras> camera = defaultCameras();
  std::shared_ptr<V4l2Device> v4l2;  // null: the kernel
  // Set: the images come from these (FileCamera) instead of the V4L2 devices.
  std::array<std::shared_ptr<CameraSource>, kNumCameras> sources;

  // Top: /dev/video-top 640x480, rotated (mounted upside down); bottom: /dev/video-bottom 320x240.
  static std::array<V4l2CameraConfig, kNumCameras> defaultCameras();
};

class NaoBackend : public Backend {
 public:
  using Log = std::function<void(const std::string&)>;
  // Connects to LoLA (throws nao::Error naming the socket when it is not there) and opens
  // the cameras (a camera that fails is retried while the program runs).
  explicit NaoBackend(NaoBackendConfig config, Log log = {});
  ~NaoBackend() override;

  std::string name() const override { return "nao"; }
  RobotInfo robotInfo() const override { return robotInfo_; }
  bool waitForSensors(SensorFrame& frame) override;
  bool takeImage(CameraId camera, CameraImage& image) override;
  void sendRequest(const JointRequest& joints, const LedRequest& leds) override;
  // To the camera source (a V4L2 camera writes them to the NAO camera's extension unit).
  void setExposureWeights(CameraId camera, const ExposureWeights& weights) override {
    if (const auto& source = cameras_[static_cast<int>(camera)]) source->setExposureWeights(weights);
  }
  std::string stopReason() const override { return stopReason_; }
  // Answers the packet waitForSensors returned soft in place, without a program's request and
  // without starting the stiffness ramp: while the robot program is still being built.
  void answerSoftInPlace();

  // SIGINT / SIGTERM: the next cycles answer soft, then waitForSensors returns false.
  static void installSignalHandlers();
  // The same for any other reason (a time limit).
  void requestStop(const std::string& reason);
  // True when the run ended on request (signal, requestStop), false after a failure.
  bool stoppedCleanly() const { return clean_; }

  // Asked once a cycle before the answer: a non-empty text means the robot falls (soft).
  void setFallMonitor(std::function<std::string()> monitor) { fallMonitor_ = std::move(monitor); }
  Safety& safety() { return safety_; }
  double now() const;  // backend seconds since start
  // CLOCK_MONOTONIC seconds of backend time 0: aligns this run's times (sensor frames, images,
  // the JSON) with another process's clock, a simulator's truth or a log.
  double clockOrigin() const { return start_; }

  // cycles: packets handed to the program; answered: of those, answered (late: after 12 ms).
  struct Stats {
    std::uint64_t packets = 0, cycles = 0, answered = 0, corrupt = 0, staleEvents = 0, skipped = 0, late = 0,
                  dropped = 0;
    double maxAnswerMs = 0, sumAnswerMs = 0;
    std::array<std::uint32_t, 1001> answerMsHistogram{};  // 0.05 ms bins; the last: 50 ms and more
    // The first late answers' packet arrival and answer (CLOCK_MONOTONIC s): a peer lines them
    // up with what else held the machine up then.
    std::vector<std::pair<double, double>> lateAnswers;
    // The answer time (ms from a packet's arrival to its answer) that q of the answers kept.
    double answerMsQuantile(double q) const;
  };
  const Stats& stats() const { return stats_; }

 private:
  void answer(const JointRequest& joints);
  void answered();
  bool finish(const std::string& reason, bool clean);
  static double monotonic();

  NaoBackendConfig config_;
  Log log_;
  Safety safety_;
  lola::LolaClient client_;
  std::array<std::shared_ptr<CameraSource>, kNumCameras> cameras_;
  double start_ = 0;
  double lastPacket_ = 0, receivedAt_ = 0;
  bool stale_ = false, awaiting_ = false, haveInfo_ = false;
  bool stopping_ = false, stopped_ = false, clean_ = false;
  int stopAnswers_ = 0;
  std::string stopReason_;
  RobotInfo robotInfo_{"unknown", "unknown", "unknown", "unknown"};
  LedRequest leds_;
  std::function<std::string()> fallMonitor_;
  std::vector<std::uint8_t> packet_;
  Stats stats_;
};

}  // namespace nao
