// sim_lola_peer: the simulator stands in for a whole NAO under `nao-soccer run --backend nao`.
// One MuJoCo NAO (the world `run --backend sim` builds) is the hardware: every 12 ms cycle the
// peer steps it, sends its sensors as a LoLA packet over a real Unix socket (the documented
// msgpack, tests/support/LolaWire.h, nothing of robot/nao/), judges the answer against the
// cycle and drives the simulated joints with it; both cameras are rendered at 30 Hz from the
// same state and sent over a second socket to the program's `--cameras socket:PATH`, which
// hands them to cognition as the V4L2 cameras do. The program never sees the truth; the peer
// records it per cycle and scores the program's own belief (its JSON's per_second) against it.
// The program runs on the LoLA clock (--clock lola, 12 ms per packet), the simulation's time:
// rendering makes this peer slower than real time, and physics must not fall behind the clock
// the walk and the filters use.
//
// usage: sim_lola_peer --nao-soccer BIN [--seconds S] [--seed N] [--pose X,Y,DEG] [--ball X,Y]
//                      [--goto X,Y,DEG] [--json FILE] [--keep] [--sanitized]
// S: simulated seconds (default 20); the program gets SIGTERM after them and must stop softly.
// While the program starts (soft, then its stiffness ramp) the peer holds the robot standing,
// as a person holds a NAO that boots. The figures go to stdout (JSON); exit 0 when every check
// passed (no missing answer, no late one outside the machine's own stalls: tests/support/StallProbe.h, a clean stop). --sanitized (the ASan + UBSan build, whose
// program and peer are several times slower): late answers are counted, not judged.
#include <pthread.h>
#include <sched.h>
#include <signal.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <random>
#include <thread>

#include <mujoco/mujoco.h>

#include <nlohmann/json.hpp>

#include "controllers/StandController.h"
#include "perception/FieldDimensions.h"
#include "robot/JointRequest.h"
#include "robot/math/Pose2.h"
#include "robot/nao/SocketCamera.h"
#include "sim/CameraRenderer.h"
#include "sim/Lighting.h"
#include "sim/SimBackend.h"
#include "sim/World.h"
#include "tests/support/LolaWire.h"
#include "tests/support/StallProbe.h"

namespace {

using namespace lola_wire;
using nao::CameraId;

struct Options {
  std::string bin;
  double seconds = 20;
  std::uint64_t seed = 1;
  Eigen::Vector3d pose{-3.2, -3.0, M_PI / 2};  // as run --backend sim: the calibration position
  std::optional<Eigen::Vector2d> ball;
  std::vector<double> goTo;  // x, y, deg
  std::string json;
  bool keep = false;
  bool sanitized = false;  // --sanitized: answer times are measured, not judged (ASan builds)
};

std::vector<double> numbers(const std::string& s) {
  std::vector<double> v;
  std::stringstream in(s);
  std::string part;
  while (std::getline(in, part, ',')) v.push_back(std::stod(part));
  return v;
}

// The camera sockets: each of the program's two cameras connects and names itself.
struct CameraLink {
  int listener = -1;
  std::array<int, 2> fd{-1, -1};
  std::array<long, 2> sent{0, 0};
  std::array<nao::ExposureWeights, 2> weights;  // what each camera's program side last sent
  std::array<long, 2> weightMessages{0, 0};
  std::array<long, 2> unevenMessages{0, 0};  // of them, weights not all equal

  void acceptPending() {
    for (;;) {
      pollfd p{listener, POLLIN, 0};
      if (::poll(&p, 1, 0) <= 0) return;
      const int c = ::accept4(listener, nullptr, nullptr, SOCK_CLOEXEC);
      if (c < 0) return;
      char hello[8] = {};
      pollfd h{c, POLLIN, 0};
      if (::poll(&h, 1, 1000) <= 0 || ::recv(c, hello, sizeof hello, MSG_WAITALL) != 8 ||
          std::memcmp(hello, "NAOCAM1", 7) != 0 || (hello[7] != 0 && hello[7] != 1)) {
        check(false, "a camera connection without the hello");
        ::close(c);
        continue;
      }
      if (fd[hello[7]] >= 0) ::close(fd[hello[7]]);
      fd[hello[7]] = c;
    }
  }

  // The auto exposure weights each camera's program side sent ("NAOW" + 16 cells), newest kept.
  void readWeights() {
    for (int cam = 0; cam < 2; ++cam) {
      std::uint8_t m[nao::kSocketWeightsSize];
      while (fd[cam] >= 0 && ::recv(fd[cam], m, sizeof m, MSG_PEEK | MSG_DONTWAIT) == static_cast<ssize_t>(sizeof m)) {
        (void)::recv(fd[cam], m, sizeof m, MSG_DONTWAIT);
        if (std::memcmp(m, nao::kSocketWeightsMagic, 4) != 0) {
          check(false, "a camera sent something that is not exposure weights");
          ::close(fd[cam]);
          fd[cam] = -1;
          break;
        }
        std::memcpy(weights[cam].cell.data(), m + 4, weights[cam].cell.size());
        ++weightMessages[cam];
        unevenMessages[cam] += !weights[cam].uniform();
      }
    }
  }

  // One frame: the header (tests/../robot/nao/SocketCamera.h's wire), then the YUYV bytes.
  void send(const nao::CameraImage& image, double captureMonotonic) {
    const int cam = static_cast<int>(image.camera);
    if (fd[cam] < 0) return;  // the camera has not connected (yet): the frame is lost, as on a robot
    std::uint8_t header[24] = {'N', 'A', 'O', 'F'};
    const std::uint32_t w = static_cast<std::uint32_t>(image.width), h = static_cast<std::uint32_t>(image.height), zero = 0;
    std::memcpy(header + 4, &w, 4);
    std::memcpy(header + 8, &h, 4);
    std::memcpy(header + 12, &zero, 4);
    std::memcpy(header + 16, &captureMonotonic, 8);
    for (const auto& [data, size] : {std::pair<const void*, std::size_t>{header, sizeof header},
                                     std::pair<const void*, std::size_t>{image.yuyv.data(), image.yuyv.size()}}) {
      std::size_t done = 0;
      while (done < size) {
        const ssize_t n = ::send(fd[cam], static_cast<const char*>(data) + done, size - done, MSG_NOSIGNAL);
        if (n <= 0) {
          ::close(fd[cam]);
          fd[cam] = -1;
          return;
        }
        done += static_cast<std::size_t>(n);
      }
    }
    ++sent[cam];
  }
};

// The cameras, rendered beside the LoLA loop: a state copied at an image's cycle is rendered on
// a model of the worker's own (the renderer writes the lights into it) while the loop goes on,
// so a render never holds a LoLA packet back. A frame whose render is still running when the
// next one is due is waited for up to 30 ms, then dropped and counted.
class RenderWorker {
 public:
  RenderWorker(const mjModel* m, nao::sim::Lighting lighting, std::uint64_t seed)
      : model_(mj_copyModel(nullptr, m)), data_(mj_makeData(model_)), lighting_(std::move(lighting)),
        rng_(seed ^ 0x9e3779b97f4a7c15ULL) {  // as run --backend sim
    thread_ = std::thread([this] { loop(); });
    // The renderer is made before the LoLA loop starts: making its context loads libOSMesa and
    // LLVM (sim/GlContext.cpp), which beside the loop held it up on the dynamic loader's lock.
    std::unique_lock<std::mutex> lock(mutex_);
    wake_.wait(lock, [this] { return ready_; });
  }
  ~RenderWorker() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
    mj_deleteData(data_);
    mj_deleteModel(model_);
  }

  // Waits up to maxWaitS for the worker; false (the frame is dropped) when it is still busy.
  bool submit(const mjModel* m, const mjData* d, CameraId camera, int mjCamera, int width, int height, double stamp,
              const nao::ExposureWeights& metering, double maxWaitS) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (!wake_.wait_for(lock, std::chrono::duration<double>(maxWaitS), [this] { return !job_ || stop_; })) return false;
    mj_copyData(data_, m, d);
    job_ = Job{camera, mjCamera, width, height, stamp, metering};
    wake_.notify_all();
    return true;
  }
  // The frames rendered since the last call, oldest first.
  std::vector<nao::CameraImage> done() {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::exchange(done_, {});
  }
  std::string error() {
    std::lock_guard<std::mutex> lock(mutex_);
    return error_;
  }

 private:
  struct Job {
    CameraId camera;
    int mjCamera, width, height;
    double stamp;
    nao::ExposureWeights metering;
  };
  void loop() {
    // The renders at normal priority, below the LoLA loop (SCHED_FIFO where allowed): they take what is left.
    setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), 0);
    std::unique_ptr<nao::sim::CameraRenderer> renderer;
    try {
      renderer = std::make_unique<nao::sim::CameraRenderer>(model_);
    } catch (const std::exception&) {
      // Made again at the first frame, whose error the loop reports.
    }
    std::unique_lock<std::mutex> lock(mutex_);
    ready_ = true;
    wake_.notify_all();
    for (;;) {
      wake_.wait(lock, [this] { return job_ || stop_; });
      if (stop_) return;
      const Job job = *job_;
      lock.unlock();  // data_ is the worker's until job_ is cleared
      nao::CameraImage image;
      std::string error;
      try {
        if (!renderer) renderer = std::make_unique<nao::sim::CameraRenderer>(model_);
        image = renderer->renderImage(model_, data_, job.mjCamera, job.width, job.height, lighting_, job.camera,
                                      job.stamp, rng_, job.metering);
        image.camera = job.camera;
        image.timestamp = job.stamp;
      } catch (const std::exception& e) {
        error = e.what();
      }
      lock.lock();
      if (error.empty()) done_.push_back(std::move(image));
      else error_ = error;
      job_.reset();
      wake_.notify_all();
    }
  }

  mjModel* model_;
  mjData* data_;
  nao::sim::Lighting lighting_;
  std::mt19937_64 rng_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<Job> job_;
  std::vector<nao::CameraImage> done_;
  std::string error_;
  bool stop_ = false, ready_ = false;
  std::thread thread_;
};

Sensors sensorsOf(const nao::SensorFrame& f, const nao::RobotInfo& info) {
  Sensors s;
  for (int j = 0; j < kJoints; ++j) {
    s.position[j] = f.joints.position[j];
    s.stiffness[j] = f.joints.stiffness[j];
    s.current[j] = f.joints.current[j];
    s.temperature[j] = f.joints.temperature[j];
  }
  for (int i = 0; i < 3; ++i) {
    s.accelerometer[i] = f.inertial.accelerometer[i];
    s.gyroscope[i] = f.inertial.gyroscope[i];
  }
  s.angles = {f.inertial.angle.x(), f.inertial.angle.y()};
  s.battery = {f.battery.charge, f.battery.status, f.battery.current, f.battery.temperature};
  for (int i = 0; i < 8; ++i) s.fsr[i] = f.fsr.weight[i];
  for (std::size_t i = 0; i < s.touch.size() && i < f.touch.size(); ++i) s.touch[i] = f.touch[i];
  s.sonar = {f.sonar[0], f.sonar[1]};
  s.robotConfig = {info.bodyId, info.bodyVersion, info.headId, info.headVersion};
  return s;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return -1;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

// The truth at one cycle, and its packet's time on the program's LoLA clock.
struct Truth {
  double time = 0;
  Eigen::Vector3d pose;
  std::optional<Eigen::Vector2d> ball;
};

int runPeer(const Options& o) {
  using namespace nao;
  const FieldDimensions field = FieldDimensions::load(std::string(NAO_SOURCE_DIR) + "/config/field_dimensions.json");
  sim::SceneSpec spec;
  spec.field = field;
  spec.robots = {o.pose};
  if (o.ball) spec.balls = {Eigen::Vector3d(o.ball->x(), o.ball->y(), 0.05)};
  sim::World world(spec, o.seed);
  world.placeRobot(0, o.pose, StandController::standPosture());
  sim::SimBackend backend(world, 0, true);
  const sim::Lighting lighting = sim::Lighting::parse("default", std::string(NAO_SOURCE_DIR) + "/config/lighting.json");
  RenderWorker render(world.model(), lighting, o.seed);
  // Each camera at 30 Hz of simulated time, the bottom one half a period after the top one.
  std::array<double, 2> nextDue = {world.time(), world.time() + kCameraPeriod / 2};
  long framesDropped = 0;
  const RobotInfo info = backend.robotInfo();

  const std::string dir = mkWorkDir();
  const std::string lolaPath = dir + "/lola.sock", cameraPath = dir + "/cameras.sock", runJson = dir + "/run.json";
  const int lolaListener = listenOn(lolaPath);
  CameraLink cameras;
  cameras.listener = listenOn(cameraPath);
  // --clock lola: the program's time advances 12 ms per packet, as the simulated physics does,
  // however long a render holds the peer up; the frames carry that clock.
  std::vector<std::string> args = {o.bin, "run", "--backend", "nao", "--cameras", "socket:" + cameraPath,
                                   "--clock", "lola", "--lola-socket", lolaPath, "--json", runJson};
  if (o.goTo.size() == 3) {
    char g[96];
    std::snprintf(g, sizeof g, "%g,%g,%g", o.goTo[0], o.goTo[1], o.goTo[2]);
    args.insert(args.end(), {"--goto", g});
  }
  Child child = spawn(args, dir + "/run.stderr");
  Peer peer(acceptClient(lolaListener, child), child);
  // On a NAO, LoLA runs at SCHED_FIFO 20-30, above the program's motion cadence (10): packets go
  // out and answers are taken on time whatever cognition does. The peer's LoLA loop does the same
  // where allowed (root), so that its answer times measure the program, not the peer's own wait
  // for a core held by its renders or the program's cognition. Set only now: the spawned program
  // would inherit it (the render thread, started before, stays at normal priority).
  sched_param rt{};
  rt.sched_priority = 20;
  const bool peerRealTime = pthread_setschedparam(pthread_self(), SCHED_FIFO, &rt) == 0;
  std::fprintf(stderr, "sim_lola_peer: LoLA loop at %s\n", peerRealTime ? "SCHED_FIFO 20" : "normal priority (not root)");
  StallProbe probe;
  std::vector<std::pair<double, double>> lateAnswers;  // [sent, answered], monotonic s

  std::vector<Truth> truths;
  std::vector<double> latencyMs;
  int late = 0, missing = 0, behind = 0;
  long packets = 0;
  bool holding = true;  // the peer's hands keep the robot standing until the program's ramp is done
  double holdEndSim = -1;
  const auto wallStart = std::chrono::steady_clock::now();
  double tick = monotonic() + 0.05;
  double nextProgress = 10;
  std::optional<Eigen::Vector3d> finalTruth;
  bool stopSent = false;
  int afterStop = 0;
  SensorFrame frame;
  while (!peer.eof() && afterStop < 400) {
    if (!backend.waitForSensors(frame)) {
      check(false, "the simulation stopped: " + backend.stopReason());
      break;
    }
    sleepUntil(tick);
    if (monotonic() - tick > kCycle) {  // a busy machine held the peer up: on from now, no burst
      tick = monotonic();
      ++behind;
    }
    tick += kCycle;
    cameras.acceptPending();
    const double sent = monotonic();
    peer.send(encodeSensors(sensorsOf(frame, info)));
    ++packets;
    const double lolaTime = static_cast<double>(packets) * kCycle;  // the program's clock for this packet
    Truth truth{lolaTime, world.robotPose(0), std::nullopt};
    if (world.ballCount() > 0) truth.ball = world.ballPosition(0).head<2>();
    truths.push_back(truth);
    Answer a;
    const bool got = peer.next(a, sent + kCycle + 0.1);
    const bool judged = !holding && !stopSent;
    if (got) {
      const double ms = (a.time - sent) * 1000;
      if (judged) {
        latencyMs.push_back(ms);
        if (ms > kCycle * 1000) {
          ++late;
          lateAnswers.emplace_back(sent, a.time);
          std::fprintf(stderr, "sim_lola_peer: answer at %.2f s simulated came after %.2f ms\n", frame.time, ms);
        }
      }
      if (holding && a.maxStiffness() >= 0.999) {
        holding = false;
        holdEndSim = frame.time;
        std::fprintf(stderr, "sim_lola_peer: the program stands on its own at %.2f s simulated\n", frame.time);
      }
      if (!holding) {
        JointRequest request;
        const auto& position = a["Position"];
        const auto& stiffness = a["Stiffness"];
        for (int j = 0; j < kJoints; ++j) {
          request.position[j] = std::isfinite(position[j]) ? position[j] : frame.joints.position[j];
          request.stiffness[j] = std::isfinite(stiffness[j]) ? stiffness[j] : 0;
        }
        backend.sendRequest(request, LedRequest{});
      }
    } else if (judged) {
      ++missing;
      check(false, fmt("no answer to the packet at %.2f s simulated", frame.time));
    }
    // Frames of this state, stamped with its packet's time on the program's clock; sent when rendered.
    cameras.readWeights();
    for (CameraId cam : {CameraId::Top, CameraId::Bottom}) {
      double& due = nextDue[static_cast<int>(cam)];
      if (frame.time + 1e-9 < due) continue;
      due += kCameraPeriod;
      const sim::CameraResolution res = world.cameraResolution(cam);
      if (!render.submit(world.model(), world.data(), cam, world.cameraIndex(0, cam), res.width, res.height, lolaTime,
                         cameras.weights[static_cast<int>(cam)], 0.03))
        ++framesDropped;
    }
    for (const CameraImage& image : render.done()) cameras.send(image, image.timestamp);
    if (const std::string e = render.error(); !e.empty()) {
      check(false, "rendering: " + e);
      break;
    }
    if (holding && frame.time > 30) {
      check(false, "the program did not take over within 30 s");
      break;
    }
    if (!stopSent && !holding && frame.time >= holdEndSim + o.seconds) {
      finalTruth = world.robotPose(0);
      kill(child.pid, SIGTERM);
      stopSent = true;
    }
    if (stopSent) ++afterStop;
    if (!holding && frame.time - holdEndSim >= nextProgress) {
      std::fprintf(stderr, "sim_lola_peer: %.0f of %.0f s simulated, %d late, frames %ld + %ld\n", nextProgress,
                   o.seconds, late, cameras.sent[0], cameras.sent[1]);
      nextProgress += 10;
    }
  }
  const double wallS = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
  check(child.exited(5000), "the program did not exit after SIGTERM");
  check(child.exitCode() == 0, "the program's exit code " + std::to_string(child.exitCode()));

  // Each late answer: was the machine itself stalled then (the probe held up)?
  int lateInStalls = 0;
  for (const auto& [from, to] : lateAnswers) lateInStalls += probe.stalledDuring(from, to);
  check(o.sanitized || late == lateInStalls,
        fmt("%.0f late answers, %.0f of them while the machine itself stalled", late, lateInStalls));
  nlohmann::json out = {{"seconds_simulated", o.seconds},
                        {"wall_s", wallS},
                        {"peer_real_time", peerRealTime},
                        {"cycles_judged", latencyMs.size() + static_cast<std::size_t>(missing)},
                        {"late_answers", late},
                        {"late_answers_in_machine_stalls", lateInStalls},
                        {"machine_stalls", probe.figures()},
                        {"missing_answers", missing},
                        {"answer_ms", {{"median", percentile(latencyMs, 0.5)}, {"p99", percentile(latencyMs, 0.99)},
                                       {"max", percentile(latencyMs, 1.0)}}},
                        {"peer_behind", behind},
                        {"frames_sent", {{"top", cameras.sent[0]}, {"bottom", cameras.sent[1]}}},
                        // The program's auto exposure weights as they came over the camera sockets.
                        {"exposure_weights",
                         {{"top", {{"messages", cameras.weightMessages[0]}, {"uneven", cameras.unevenMessages[0]},
                                   {"last", cameras.weights[0].cell}}},
                          {"bottom", {{"messages", cameras.weightMessages[1]}, {"uneven", cameras.unevenMessages[1]},
                                      {"last", cameras.weights[1].cell}}}}},
                        {"frames_dropped", framesDropped},
                        {"work_dir", dir}};
  std::ifstream runFile(runJson);
  nlohmann::json run;
  if (check(runFile.good(), "the program wrote no JSON")) {
    run = nlohmann::json::parse(runFile, nullptr, false);
    check(!run.is_discarded(), "the program's JSON does not parse");
  }
  if (run.is_object()) {
    out["program"] = {{"lola", run["lola"]},
                      {"images_processed", run["images_processed"]},
                      {"images_dropped", run["images_dropped"]},
                      {"images_skipped", run["images_skipped"]},
                      {"cognition", run["cognition"]},
                      {"clean_stop", run["clean_stop"]}};
    // The program's own late answers (packet arrival to answer, its clock) likewise: only
    // while the machine itself stalled.
    int programLateInStalls = 0;
    for (const auto& t : run["lola"].value("late_answer_times", nlohmann::json::array()))
      programLateInStalls += probe.stalledDuring(t[0].get<double>(), t[1].get<double>());
    out["program_late_in_machine_stalls"] = programLateInStalls;
    check(o.sanitized || run["lola"].value("late", -1) == programLateInStalls,
          fmt("the program counted %.0f late answers, %.0f of them while the machine stalled", run["lola"].value("late", -1),
              programLateInStalls));
    // The belief once a second against the truth of the cycle whose packet its image carried.
    check(run.value("clock", "") == "lola", "the program did not run on the LoLA clock");
    std::vector<double> position, heading, ballErrors;
    long beliefs = 0, valid = 0;
    nlohmann::json perSecond = nlohmann::json::array();
    for (const auto& b : run["per_second"]) {
      const double t = b["image_time"].get<double>();
      if (t < 2 || holdEndSim < 0) continue;  // as run --backend sim: after the first 2 s
      const auto packet = static_cast<std::size_t>(std::lround(t / kCycle));
      if (packet < 1 || packet > truths.size()) continue;
      const auto it = truths.begin() + static_cast<long>(packet - 1);
      ++beliefs;
      nlohmann::json second = {{"t", t},
                               {"true_pose", {it->pose.x(), it->pose.y(), it->pose.z() * 180 / M_PI}},
                               {"estimated_pose", b["estimated_pose"]},
                               {"valid", b["valid"]}};
      if (it->ball) second["true_ball"] = {it->ball->x(), it->ball->y()};
      if (b.contains("ball")) second["ball"] = b["ball"];
      perSecond.push_back(second);
      if (!b["valid"].get<bool>()) continue;
      ++valid;
      const auto& e = b["estimated_pose"];
      const Pose2 estimate(e[0].get<double>(), e[1].get<double>(), e[2].get<double>() * M_PI / 180);
      position.push_back(std::hypot(estimate.x - it->pose.x(), estimate.y - it->pose.y()));
      heading.push_back(std::abs(Pose2::wrap(estimate.theta - it->pose.z())) * 180 / M_PI);
      if (it->ball && b.contains("ball") && b["ball"]["valid"].get<bool>() && !b["ball"]["lost"].get<bool>()) {
        const Eigen::Vector2d model(b["ball"]["position"][0].get<double>(), b["ball"]["position"][1].get<double>());
        const Eigen::Vector2d truthRelative = Pose2(it->pose.x(), it->pose.y(), it->pose.z()).inverse() * *it->ball;
        ballErrors.push_back((model - truthRelative).norm());
      }
    }
    out["beliefs"] = beliefs;
    out["per_second"] = perSecond;  // the program's belief beside the truth (field frame; ball: robot frame)
    out["localization_valid_fraction"] = beliefs ? static_cast<double>(valid) / static_cast<double>(beliefs) : 0.0;
    out["localization_error_m"] = {{"median", percentile(position, 0.5)}, {"p95", percentile(position, 0.95)},
                                   {"max", percentile(position, 1.0)}};
    out["heading_error_deg"] = {{"median", percentile(heading, 0.5)}, {"p95", percentile(heading, 0.95)}};
    out["ball_error_m"] = {{"median", percentile(ballErrors, 0.5)}, {"p95", percentile(ballErrors, 0.95)},
                           {"samples", ballErrors.size()}};
    if (finalTruth) out["final_true_pose"] = {finalTruth->x(), finalTruth->y(), finalTruth->z() * 180 / M_PI};
    if (run.contains("final_estimated_pose")) out["final_estimated_pose"] = run["final_estimated_pose"];
    if (o.goTo.size() == 3 && finalTruth) {
      const double dx = finalTruth->x() - o.goTo[0], dy = finalTruth->y() - o.goTo[1];
      const double dh = std::abs(Pose2::wrap(finalTruth->z() - o.goTo[2] * M_PI / 180)) * 180 / M_PI;
      out["goto"] = {{"target", o.goTo}, {"position_error_m", std::hypot(dx, dy)}, {"heading_error_deg", dh}};
    }
  }
  out["checks_failed"] = check.failures.size();
  std::printf("%s\n", out.dump(1).c_str());
  if (!o.json.empty()) std::ofstream(o.json) << out.dump(1) << "\n";
  if (!check.failures.empty()) std::fprintf(stderr, "sim_lola_peer: the program's stderr:\n%s\n", child.stderrText().c_str());
  if (check.failures.empty() && !o.keep) std::system(("rm -rf '" + dir + "'").c_str());
  return check.failures.empty() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      const bool value = i + 1 < argc;
      if (a == "--nao-soccer" && value) o.bin = argv[++i];
      else if (a == "--seconds" && value) o.seconds = std::stod(argv[++i]);
      else if (a == "--seed" && value) o.seed = std::stoull(argv[++i]);
      else if (a == "--pose" && value) {
        const auto v = numbers(argv[++i]);
        if (v.size() != 3) throw std::invalid_argument("--pose X,Y,DEG");
        o.pose = Eigen::Vector3d(v[0], v[1], v[2] * M_PI / 180);
      } else if (a == "--ball" && value) {
        const auto v = numbers(argv[++i]);
        if (v.size() != 2) throw std::invalid_argument("--ball X,Y");
        o.ball = Eigen::Vector2d(v[0], v[1]);
      } else if (a == "--goto" && value) {
        o.goTo = numbers(argv[++i]);
        if (o.goTo.size() != 3) throw std::invalid_argument("--goto X,Y,DEG");
      } else if (a == "--json" && value) o.json = argv[++i];
      else if (a == "--keep") o.keep = true;
      else if (a == "--sanitized") o.sanitized = true;
      else throw std::invalid_argument(a);
    }
    if (o.bin.empty() || !(o.seconds >= 1 && o.seconds <= 3600)) throw std::invalid_argument("--nao-soccer BIN, --seconds 1..3600");
  } catch (const std::exception& e) {
    std::fprintf(stderr,
                 "sim_lola_peer: %s\nusage: sim_lola_peer --nao-soccer BIN [--seconds S] [--seed N] [--pose X,Y,DEG] "
                 "[--ball X,Y] [--goto X,Y,DEG] [--json FILE] [--keep] [--sanitized]\n",
                 e.what());
    return 2;
  }
  signal(SIGPIPE, SIG_IGN);
  if (const int parentExit = runInAHighPrioritySession("sim_lola_peer"); parentExit >= 0) return parentExit;
  try {
    return runPeer(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sim_lola_peer: %s\n", e.what());
    return 2;
  }
}
