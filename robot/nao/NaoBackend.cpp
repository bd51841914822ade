#include "robot/nao/NaoBackend.h"

#include <signal.h>
#include <time.h>

#include <atomic>
#include <cmath>
#include <cstdio>

#include "robot/Error.h"

namespace nao {
namespace {

std::atomic<int> g_signal{0};

extern "C" void onStopSignal(int sig) { g_signal.store(sig); }

std::string ms(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f ms", seconds * 1000);
  return text;
}

}  // namespace

std::array<V4l2CameraConfig, kNumCameras> NaoBackendConfig::defaultCameras() {
  std::array<V4l2CameraConfig, kNumCameras> c;
  c[0].camera = CameraId::Top;
  c[0].device = "/dev/video-top";
  c[0].width = 640;
  c[0].height = 480;
  c[0].rotate180 = true;
  c[1].camera = CameraId::Bottom;
  c[1].device = "/dev/video-bottom";
  c[1].width = 320;
  c[1].height = 240;
  return c;
}

void NaoBackend::installSignalHandlers() {
  struct sigaction sa {};
  sa.sa_handler = onStopSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;  // no SA_RESTART: a blocked poll returns at once
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

double NaoBackend::monotonic() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);  // the clock V4L2 stamps its buffers with
  return static_cast<double>(ts.tv_sec) + ts.tv_nsec * 1e-9;
}

double NaoBackend::now() const { return monotonic() - start_; }

NaoBackend::NaoBackend(NaoBackendConfig config, Log log)
    : config_(std::move(config)),
      log_(log ? std::move(log) : Log([](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); })),
      safety_(config_.safety, log_),
      client_(config_.lolaSocket) {
  start_ = monotonic();
  log_("lola: connecting to " + config_.lolaSocket);
  client_.connect(config_.connectTimeout, [] { return g_signal.load() != 0; });
  log_("lola: connected");
  lastPacket_ = now();
  if (config_.sources[0] || config_.sources[1]) {
    cameras_ = config_.sources;
  } else if (config_.cameras) {
    auto device = config_.v4l2 ? config_.v4l2 : kernelV4l2Device();
    for (int c = 0; c < kNumCameras; ++c) {
      auto camera = std::make_shared<V4l2Camera>(device, config_.camera[c], log_);
      camera->open(monotonic());  // a failure is logged; grab() retries
      cameras_[c] = std::move(camera);
    }
  }
}

NaoBackend::~NaoBackend() = default;

void NaoBackend::requestStop(const std::string& reason) {
  if (stopping_) return;
  stopping_ = true;
  stopReason_ = reason;
  safety_.fault(SafetyFault::Stop, "stopping: " + reason);
}

bool NaoBackend::finish(const std::string& reason, bool clean) {
  stopped_ = true;
  clean_ = clean;
  stopReason_ = reason;
  return false;
}

void NaoBackend::answer(const JointRequest& out) {
  lola::ActuatorPacket p;
  p.position = out.position;
  p.stiffness = out.stiffness;
  p.leds = leds_;
  std::string error;
  if (!client_.write(lola::encodeActuatorPacket(p), error)) {
    ++stats_.dropped;
    if (!client_.connected()) safety_.fault(SafetyFault::SocketClosed, error);
    else if (stats_.dropped == 1 || stats_.dropped % 100 == 0) log_("lola: " + error + " (" + std::to_string(stats_.dropped) + " so far)");
  }
}

bool NaoBackend::waitForSensors(SensorFrame& frame) {
  if (stopped_) return false;
  const double staleTime = config_.staleCycles * kCycleTime;
  for (;;) {
    if (const int sig = g_signal.load(); sig != 0 && !stopping_) {
      stopping_ = true;
      stopReason_ = sig == SIGINT ? "SIGINT received" : "SIGTERM received";
      safety_.fault(SafetyFault::Signal, stopReason_ + ": stopping");
    }
    if (stopping_ && stopAnswers_ >= config_.stopCycles) return finish(stopReason_, true);
    if (!client_.connected()) return finish(safety_.reason().empty() ? "LoLA socket closed" : safety_.reason(), stopping_);

    // Wait for the next packet until it is overdue; while stale, answer softly once a cycle.
    // Before the first packet nothing was measured, so there is nothing to hold: just wait.
    const double due = !safety_.hasMeasurement() ? 0.1 : stale_ ? kCycleTime : lastPacket_ + staleTime - now();
    const int timeoutMs = std::max(0, static_cast<int>(std::ceil(due * 1000)));
    std::string error;
    const auto r = client_.read(packet_, timeoutMs, error);
    const double t = now();
    switch (r) {
      case lola::LolaClient::Read::Interrupted: continue;
      case lola::LolaClient::Read::Closed:
        safety_.fault(SafetyFault::SocketClosed, error);
        answer(safety_.softInPlace());  // best effort: LoLA may only have shut down its side
        return finish(error, stopping_);
      case lola::LolaClient::Read::Timeout:
        if (!safety_.hasMeasurement()) {
          if (stopping_) return finish(stopReason_, true);
          continue;
        }
        if (t - lastPacket_ < staleTime) continue;
        if (!stale_) ++stats_.staleEvents;
        stale_ = true;
        safety_.fault(SafetyFault::StaleSensors,
                      "stale sensor data: no LoLA packet for more than " + ms(staleTime) + " (" +
                          std::to_string(config_.staleCycles) + " cycles)");
        answer(safety_.softInPlace());
        if (stopping_) ++stopAnswers_;
        continue;
      case lola::LolaClient::Read::Corrupt:
      case lola::LolaClient::Read::Packet: break;
    }
    lastPacket_ = t;
    if (stale_) log_("lola: sensor data flows again");
    stale_ = false;
    ++stats_.packets;
    lola::SensorPacket sensors;
    bool ok = r == lola::LolaClient::Read::Packet;
    if (ok) {
      try {
        sensors = lola::decodeSensorPacket(packet_.data(), packet_.size());
      } catch (const Error& e) {
        error = e.what();
        ok = false;
      }
    }
    if (!ok) {
      ++stats_.corrupt;
      safety_.fault(SafetyFault::CorruptPacket, "corrupt LoLA packet: " + error);
      answer(safety_.softInPlace());
      if (stopping_) ++stopAnswers_;
      continue;
    }
    safety_.sensorsOk(sensors.position);
    if (!haveInfo_) {
      robotInfo_ = lola::toRobotInfo(sensors);
      haveInfo_ = true;
      log_("lola: body " + robotInfo_.bodyId + " (" + robotInfo_.bodyVersion + "), head " + robotInfo_.headId + " (" +
           robotInfo_.headVersion + ")");
    }
    if (stopping_) {
      answer(safety_.softInPlace());
      ++stopAnswers_;
      continue;
    }
    if (client_.packetBuffered()) {
      ++stats_.skipped;  // the program is behind LoLA: answer the newest packet only
      continue;
    }
    lola::toSensorFrame(sensors, frame);
    frame.time = config_.lolaClock ? static_cast<double>(stats_.packets) * kCycleTime : t;
    frame.cycle = ++stats_.cycles;
    receivedAt_ = t;
    awaiting_ = true;
    return true;
  }
}

bool NaoBackend::takeImage(CameraId camera, CameraImage& image) {
  auto& cam = cameras_[static_cast<int>(camera)];
  if (!cam) return false;
  // On the LoLA clock (--clock lola) the frames are due on it too: the time of this cycle's packet.
  if (!cam->grab(image, config_.lolaClock ? static_cast<double>(stats_.packets) * kCycleTime : monotonic())) return false;
  if (!config_.lolaClock) image.timestamp -= start_;
  return true;
}

void NaoBackend::sendRequest(const JointRequest& joints, const LedRequest& leds) {
  if (!awaiting_) return;  // one answer per sensor packet
  awaiting_ = false;
  leds_ = leds;
  if (fallMonitor_) {
    if (const std::string fall = fallMonitor_(); !fall.empty()) safety_.fault(SafetyFault::Fall, "fall: " + fall);
  }
  for (int j = 0; j < NumJoints; ++j)
    if (!std::isfinite(joints.position[j])) {
      safety_.fault(SafetyFault::BadRequest,
                    "the robot program asked for a non-finite " + std::string(kJointNames[j]) + " position");
      break;
    }
  answer(safety_.apply(joints));
  answered();
}

void NaoBackend::answerSoftInPlace() {
  if (!awaiting_) return;
  awaiting_ = false;
  answer(safety_.softInPlace());
  safety_.restartRamp();  // the ramp starts from the angles measured when the program takes over
  answered();
}

void NaoBackend::answered() {
  const double answeredAt = now();
  const double answerMs = (answeredAt - receivedAt_) * 1000;
  ++stats_.answered;
  stats_.maxAnswerMs = std::max(stats_.maxAnswerMs, answerMs);
  stats_.sumAnswerMs += answerMs;
  if (answerMs > kCycleTime * 1000) {
    ++stats_.late;
    if (stats_.lateAnswers.size() < 1000) stats_.lateAnswers.emplace_back(start_ + receivedAt_, start_ + answeredAt);
  }
  auto& h = stats_.answerMsHistogram;
  ++h[std::min(h.size() - 1, static_cast<std::size_t>(std::max(0.0, answerMs) / 0.05))];
}

double NaoBackend::Stats::answerMsQuantile(double q) const {
  std::uint64_t total = 0;
  for (auto n : answerMsHistogram) total += n;
  if (total == 0) return 0;
  const auto wanted = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(total)));
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < answerMsHistogram.size(); ++i) {
    seen += answerMsHistogram[i];
    if (seen >= std::max<std::uint64_t>(wanted, 1)) return (static_cast<double>(i) + 1) * 0.05;  // the bin's upper end
  }
  return static_cast<double>(answerMsHistogram.size()) * 0.05;
}

}  // namespace nao
