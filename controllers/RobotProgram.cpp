#include "controllers/RobotProgram.h"

#include <chrono>
#include <set>

#include "controllers/modules/ModuleField.h"
#include "representations/behavior/BehaviorCommand.h"
#include "representations/infrastructure/CurrentImage.h"
#include "representations/infrastructure/FrameHistory.h"
#include "representations/infrastructure/GameState.h"
#include "robot/ModuleRegistry.h"
#include "robot/Paths.h"

namespace nao {

namespace {

template <class... T>
struct TypeList {};

// What crosses between the cadences (docs/architecture.md). Motion to cognition: the state
// cognition interprets its images with; the calibration, the game state and the operator's
// command that the app sets. Cognition to motion: the
// behaviour's requests.
using MotionToCognition =
    TypeList<FrameHistory, Odometry, MotionInfo, FallState, CameraCalibration, GameState, BehaviorCommand>;
using CognitionToMotion = TypeList<MotionRequest, HeadMotionRequest>;

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
  if (config.field) context.params[modules::kFieldParams] = *config.field;
  context.debug = debug_ = config.debug;
  motion_.setDebug(config.debug, "motion");
  cognition_.setDebug(config.debug, "cognition");

  motionBoard_.write<CameraCalibration>() = config.calibration;
  motionBoard_.write<MotionRequest>() = MotionRequest{};  // stand
  motionBoard_.write<HeadMotionRequest>() = HeadMotionRequest{};
  motionBoard_.write<GameState>() = GameState{};
  motionBoard_.write<BehaviorCommand>().goTo = config.goTo;
  // Motion's inputs: what the cycle writes (backend), what the app sets (calibration, game state), and the
  // behaviour's requests: copied from cognition when a cognition module provides them, else
  // written by a scenario, a test or the app.
  motion_.inputs<SensorFrame, CameraImages, CameraCalibration, MotionRequest, HeadMotionRequest, GameState,
                  BehaviorCommand>();
  std::set<std::type_index> motionHas = {typeid(SensorFrame), typeid(CameraImages), typeid(CameraCalibration),
                                         typeid(MotionRequest), typeid(HeadMotionRequest), typeid(GameState),
                                         typeid(BehaviorCommand)};
  std::set<std::type_index> cognitionHas;
  for (const std::string& name : chosenModules(providers)) {
    std::unique_ptr<ModuleBase> m = createModule(name, context);
    auto& has = m->cadence() == Cadence::Motion ? motionHas : cognitionHas;
    for (const auto& t : m->provided()) has.insert(t.type);
    (m->cadence() == Cadence::Motion ? motion_ : cognition_).add(std::move(m));
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
  motion_.writeTimingSummary();
  cognition_.writeTimingSummary();
}

std::vector<std::string> RobotProgram::moduleOrder() const {
  std::vector<std::string> names = motion_.order();
  for (const auto& n : cognition_.order()) names.push_back(n);
  return names;
}

void RobotProgram::runCognition(const CameraImage& image) {
  const int cam = static_cast<int>(image.camera);
  // An image older than the last of its camera (a backend's clock gone back, a replay out of
  // order) would pair with the wrong joints: skipped.
  if (cognitionRuns_[cam] > 0 && !(image.timestamp >= lastImageTime_[cam])) {
    ++skippedImages_;
    return;
  }
  lastImageTime_[cam] = image.timestamp;
  if (debug_) debug_->setTime(image.timestamp);
  for (const auto& c : toCognition_) c.copy(motionBoard_, cognitionBoard_);
  cognitionBoard_.write<CurrentImage>().image = image;
  cognition_.update(cognitionBoard_);
  for (const auto& c : toMotion_) c.copy(cognitionBoard_, motionBoard_);
  ++cognitionRuns_[cam];
  if (observer_) observer_(image, cognitionBoard_);
}

bool RobotProgram::cycle(Backend& backend) {
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
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  motion_.update(motionBoard_);
  // The answer goes out before cognition runs: an image never delays it.
  backend.sendRequest(motionBoard_.read<JointRequest>(), motionBoard_.write<LedRequest>());
  auto last = Clock::now();
  timing_.motionMs = std::chrono::duration<double, std::milli>(last - start).count();
  timing_.cognitionMs.clear();
  if (!cognition_.modules().empty())
    for (const auto& img : images.latest)
      if (img) {
        runCognition(*img);
        const auto now = Clock::now();
        timing_.cognitionMs.push_back(std::chrono::duration<double, std::milli>(now - last).count());
        last = now;
      }
  return true;
}

}  // namespace nao
