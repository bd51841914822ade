#include "controllers/RobotProgram.h"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <set>

#include "controllers/modules/ModuleField.h"
#include "representations/behavior/ArmMotionRequest.h"
#include "representations/behavior/BehaviorCommand.h"
#include "representations/behavior/SpeechRequest.h"
#include "representations/infrastructure/AutoExposureWeights.h"
#include "representations/infrastructure/CurrentImage.h"
#include "representations/infrastructure/FrameHistory.h"
#include "representations/infrastructure/GameControllerData.h"
#include "representations/infrastructure/ChallengeMode.h"
#include "representations/perception/CalibrationStatus.h"
#include "representations/infrastructure/GameState.h"
#include "representations/infrastructure/SafetyState.h"
#include "representations/perception/VisionGeometry.h"
#include "robot/ModuleRegistry.h"
#include "robot/Paths.h"

namespace nao {

namespace {

template <class... T>
struct TypeList {};

// What crosses between the cadences (docs/architecture.md). Motion to cognition: the state
// cognition interprets its images with, the calibration the app sets, the game state and the
// operator's command. Cognition to motion: the behaviour's requests and the cameras' exposure
// weights (handed to the backend).
using MotionToCognition =
    TypeList<FrameHistory, Odometry, MotionInfo, FallState, CameraCalibration, GameState, BehaviorCommand, ChallengeMode>;
using CognitionToMotion = TypeList<MotionRequest, HeadMotionRequest, ArmMotionRequest, SpeechRequest, CalibrationStatus,
                                   AutoExposureWeights>;

template <class T>
void copyOne(const Blackboard& from, Blackboard& to) {
  to.write<T>() = from.read<T>();
}

// The crossings of `list` whose type the source side has (provides, or holds as an input).
template <class... T>
std::vector<std::pair<RepresentationType, void (*)(const Blackboard&, Blackboard&)>> crossings(
    TypeList<T...>, const std::set<std::type_index>& available) {
  std::vector<std::pair<RepresentationType, void (*)(const Blackboard&, Blackboard&)>> out;
  ((available.count(typeid(T)) ? void(out.emplace_back(RepresentationType::of<T>(), &copyOne<T>)) : void()), ...);
  return out;
}

}  // namespace

std::string RobotProgramConfig::defaultConfigDir() { return dataPath("config"); }

RobotProgram::RobotProgram(const RobotProgramConfig& config) {
  const std::string dir = config.configDir.empty() ? RobotProgramConfig::defaultConfigDir() : config.configDir;
  ProviderMap providers = loadProviders(dir + "/modules.json");
  overrideProviders(providers, config.providers, "RobotProgramConfig.providers");

  ModuleContext context;
  if (!config.configDir.empty()) context.configDir = config.configDir;
  context.headId = config.headId;
  if (config.motion) context.params["MotionEngine"] = *config.motion;
  if (config.calibrator) context.params["Calibrator"] = *config.calibrator;
  if (config.behavior) context.params["BehaviorControl"] = *config.behavior;
  if (config.field) context.params[modules::kFieldParams] = *config.field;
  context.seed = config.seed;
  context.params["CameraCalibrationProvider"] = config.calibration;
  context.debug = debug_ = config.debug;
  motion_.setDebug(config.debug, "motion");
  cognition_.setDebug(config.debug, "cognition");

  motionBoard_.write<MotionRequest>() = MotionRequest{};  // stand
  motionBoard_.write<HeadMotionRequest>() = HeadMotionRequest{};
  motionBoard_.write<ArmMotionRequest>() = ArmMotionRequest{};
  motionBoard_.write<SpeechRequest>() = SpeechRequest{};
  motionBoard_.write<GameControllerData>() = GameControllerData{};
  motionBoard_.write<SafetyState>() = SafetyState{};
  motionBoard_.write<BehaviorCommand>().goTo = config.goTo;
  // Motion's inputs: what the cycle writes (backend), what the app sets (calibration, what the
  // GameController said, the backend's safety, the operator's command), and the behaviour's
  // requests: copied from cognition when a cognition module provides them, else written by a
  // scenario, a test or the app.
  motion_.inputs<SensorFrame, CameraImages, MotionRequest, HeadMotionRequest, ArmMotionRequest, SpeechRequest,
                 GameControllerData, SafetyState, BehaviorCommand>();
  std::set<std::type_index> motionHas = {typeid(SensorFrame),        typeid(CameraImages),     typeid(MotionRequest),
                                         typeid(HeadMotionRequest),  typeid(ArmMotionRequest), typeid(SpeechRequest),
                                         typeid(GameControllerData), typeid(SafetyState),      typeid(BehaviorCommand)};
  std::set<std::type_index> cognitionHas;
  for (const std::string& name : chosenModules(providers)) {
    std::unique_ptr<ModuleBase> m = createModule(name, context);
    auto& has = m->cadence() == Cadence::Motion ? motionHas : cognitionHas;
    for (const auto& t : m->provided()) has.insert(t.type);
    (m->cadence() == Cadence::Motion ? motion_ : cognition_).add(std::move(m));
  }
  // Without CameraCalibrationProvider the calibration is the one the program was built with;
  // the calibrator's status comes from cognition when a module there provides it.
  if (!motionHas.count(typeid(CameraCalibration))) {
    motionBoard_.write<CameraCalibration>() = config.calibration;
    motion_.inputs<CameraCalibration>();
    motionHas.insert(typeid(CameraCalibration));
  }
  motionBoard_.write<CalibrationStatus>() = CalibrationStatus{};
  if (!motionHas.count(typeid(CalibrationStatus))) {
    motion_.inputs<CalibrationStatus>();
    motionHas.insert(typeid(CalibrationStatus));
  }
  // A configuration without GameStateProvider: the game state stays the default (INITIAL).
  if (!motionHas.count(typeid(GameState))) {
    motionBoard_.write<GameState>() = GameState{};
    motion_.inputs<GameState>();
    motionHas.insert(typeid(GameState));
  }
  motion_.sort();

  for (const auto& [type, copy] : crossings(MotionToCognition{}, motionHas)) {
    toCognition_.push_back({type, copy});
    cognition_.input(type);
  }
  cognition_.inputs<CurrentImage>();
  for (const auto& [type, copy] : crossings(CognitionToMotion{}, cognitionHas)) toMotion_.push_back({type, copy});
  cognition_.sort();
}

RobotProgram::~RobotProgram() {
  stopCognitionThread();
  motion_.writeTimingSummary();
  cognition_.writeTimingSummary();
}

std::vector<std::string> RobotProgram::moduleOrder() const {
  std::vector<std::string> names = motion_.order();
  for (const auto& n : cognition_.order()) names.push_back(n);
  return names;
}


void RobotProgram::runCognition(const Blackboard& exchange, const CameraImage& image) {
  const int cam = static_cast<int>(image.camera);
  // An image older than the last of its camera (a backend's clock gone back, a replay out of
  // order) would pair with the wrong joints: skipped.
  if (cognitionRuns_[cam] > 0 && !(image.timestamp >= lastImageTime_[cam])) {
    ++skippedImages_;
    return;
  }
  lastImageTime_[cam] = image.timestamp;
  if (debug_) debug_->setTime(image.timestamp);
  for (const auto& c : toCognition_) c.copy(exchange, cognitionBoard_);
  cognitionBoard_.write<CurrentImage>().image = image;
  cognition_.update(cognitionBoard_);
  ++cognitionRuns_[cam];
  if (observer_) observer_(image, cognitionBoard_);
}

bool RobotProgram::cycle(Backend& backend) {
  if (threaded_ && threaded_->failed.load(std::memory_order_acquire)) std::rethrow_exception(threaded_->error);
  auto& frame = motionBoard_.write<SensorFrame>();
  if (!backend.waitForSensors(frame)) return false;
  if (debug_) debug_->setTime(frame.time);
  auto& images = motionBoard_.write<CameraImages>();
  for (CameraId cam : {CameraId::Top, CameraId::Bottom}) {
    CameraImage img;
    auto& slot = images.latest[static_cast<int>(cam)];
    if (backend.takeImage(cam, img))
      slot = std::move(img);
    else
      slot.reset();
  }
  if (threaded_ && !toMotion_.empty()) {
    // Cognition's newest requests; while it is copying them, this cycle keeps the last ones.
    std::unique_lock<std::mutex> lock(threaded_->requestsMutex, std::try_to_lock);
    if (lock.owns_lock() && threaded_->fresh) {
      for (const auto& c : toMotion_) c.copy(threaded_->requests, motionBoard_);
      threaded_->fresh = false;
    }
  }
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  motion_.update(motionBoard_);
  // The answer goes out before cognition runs: an image never delays it.
  backend.sendRequest(motionBoard_.read<JointRequest>(), motionBoard_.write<LedRequest>());
  // The cameras' exposure weights as cognition chose them last, to the cameras when they
  // changed: after the answer (on a NAO each is a USB control transfer).
  if (motionBoard_.has<AutoExposureWeights>()) {
    const AutoExposureWeights& weights = motionBoard_.read<AutoExposureWeights>();
    for (int c = 0; c < kNumCameras; ++c)
      if (weights.camera[c] != sentExposureWeights_[c]) {
        backend.setExposureWeights(static_cast<CameraId>(c), weights.camera[c]);
        sentExposureWeights_[c] = weights.camera[c];
      }
  }
  auto last = Clock::now();
  timing_.motionMs = std::chrono::duration<double, std::milli>(last - start).count();
  timing_.cognitionMs.clear();
  if (cognition_.modules().empty()) return true;
  if (threaded_) {
    for (auto& img : images.latest)
      if (img) handOff(*img);
    return true;
  }
  for (const auto& img : images.latest)
    if (img) {
      runCognition(motionBoard_, *img);
      for (const auto& c : toMotion_) c.copy(cognitionBoard_, motionBoard_);
      const auto now = Clock::now();
      timing_.cognitionMs.push_back(std::chrono::duration<double, std::milli>(now - last).count());
      last = now;
    }
  return true;
}

// ---- the threaded form ----------------------------------------------------------------------

namespace {
double threadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}
}  // namespace

void RobotProgram::startCognitionThread() {
  if (threaded_) return;
  threaded_ = std::make_unique<Threads>();
  if (cognition_.modules().empty()) return;  // nothing to run: no thread
  threaded_->cognition = std::thread([this] { cognitionLoop(); });
}

void RobotProgram::stopCognitionThread() {
  if (!threaded_ || !threaded_->cognition.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(threaded_->jobsMutex);
    threaded_->stop = true;
  }
  threaded_->wake.notify_one();
  threaded_->cognition.join();
}

std::array<long, kNumCameras> RobotProgram::droppedImages() const {
  if (!threaded_) return {};
  std::lock_guard<std::mutex> lock(threaded_->jobsMutex);
  return threaded_->dropped;
}

// Motion's side: the image and a snapshot of the exchange into this camera's staging buffer
// (outside the lock), then swapped into the pending slot; one still pending there is dropped.
void RobotProgram::handOff(const CameraImage& image) {
  Threads& t = *threaded_;
  const int cam = static_cast<int>(image.camera);
  Job& job = t.staging[cam];
  job.image = image;  // into the buffer's own capacity
  for (const auto& c : toCognition_) c.copy(motionBoard_, job.exchange);
  {
    std::lock_guard<std::mutex> lock(t.jobsMutex);
    std::swap(job, t.pending[cam]);
    if (t.full[cam]) ++t.dropped[cam];
    t.full[cam] = true;
  }
  t.wake.notify_one();
}

void RobotProgram::cognitionLoop() {
  Threads& t = *threaded_;
  try {
    for (;;) {
      {
        std::unique_lock<std::mutex> lock(t.jobsMutex);
        t.wake.wait(lock, [&t] { return t.stop || t.full[0] || t.full[1]; });
        if (t.stop) return;
        // Both cameras waiting: the earlier exposure first, as they were taken.
        int cam = t.full[0] ? 0 : 1;
        if (t.full[0] && t.full[1] && t.pending[1].image.timestamp < t.pending[0].image.timestamp) cam = 1;
        std::swap(t.working, t.pending[cam]);
        t.full[cam] = false;
      }
      const auto wall0 = std::chrono::steady_clock::now();
      const double cpu0 = threadCpuMs();
      runCognition(t.working.exchange, t.working.image);
      const double wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall0).count();
      cognitionTime_.wallMsSum += wallMs;
      cognitionTime_.wallMsMax = std::max(cognitionTime_.wallMsMax, wallMs);
      cognitionTime_.cpuMsSum += threadCpuMs() - cpu0;
      if (!toMotion_.empty()) {
        std::lock_guard<std::mutex> lock(t.requestsMutex);
        for (const auto& c : toMotion_) c.copy(cognitionBoard_, t.requests);
        t.fresh = true;
      }
    }
  } catch (...) {
    // Motion rethrows it at its next cycle (the run fails as in the lock-step form).
    t.error = std::current_exception();
    t.failed.store(true, std::memory_order_release);
  }
}

}  // namespace nao
