#include "perception/vision/CameraPipeline.h"

#include <chrono>

#include "robot/Error.h"
#include "robot/Paths.h"

// The vision modules register themselves (NAO_REGISTER_MODULE) and nothing else names them; a
// program that uses the camera pipeline must keep them, so this file refers to each one's
// anchor (perception/vision/modules/<Name>.cpp).
#define NAO_VISION_MODULES(X)                                                                       \
  X(ImageDenoiser) X(ScanGridProvider) X(ScanLineRegionProvider) X(FieldBoundaryProvider) X(ScanLineRegionCutter)    \
  X(ObstaclePerceptor) X(FieldColourReferenceProvider) X(BallPerceptor) X(LineSpotProvider)          \
  X(CirclePerceptor) X(LinePerceptor) X(IntersectionPerceptor) X(PenaltyMarkPerceptor)               \
  X(GoalBoxSidePerceptor) X(CameraPerceptsProvider)
#define NAO_DECLARE_ANCHOR(Name) extern "C" void nao_module_##Name();
NAO_VISION_MODULES(NAO_DECLARE_ANCHOR)
#undef NAO_DECLARE_ANCHOR

namespace nao {

namespace {

#define NAO_ANCHOR(Name) &nao_module_##Name,
void (*const volatile kVisionModuleAnchors[])() = {NAO_VISION_MODULES(NAO_ANCHOR)};
#undef NAO_ANCHOR

// Reads the anchors (volatile reads the compiler must keep), so the linker keeps the modules.
bool visionModulesLinked() {
  bool all = true;
  for (const auto& anchor : kVisionModuleAnchors) all = all && anchor != nullptr;
  return all;
}

using Clock = std::chrono::steady_clock;
double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

}  // namespace

VisionGeometry VisionGeometry::from(const FieldDimensions& d) {
  VisionGeometry g;
  g.lineWidth = d.lineWidth;
  g.circleRadius = FieldModel::from(d).centerCircleRadius;
  g.penaltyCrossSize = d.penaltyCrossSize;
  return g;
}

std::string CameraPipeline::defaultProvidersFile() { return dataPath("config/camera_modules.json"); }

CameraPipeline::CameraPipeline(CameraId camera, const FieldDimensions& field, const CameraPipelineConfig& config)
    : CameraPipeline(camera, VisionGeometry::from(field), config) {}

CameraPipeline::CameraPipeline(CameraId camera, const VisionGeometry& geometry, const CameraPipelineConfig& config)
    : camera_(camera), geometry_(geometry) {
  if (!visionModulesLinked()) throw Error("camera pipeline", "vision modules not linked");
  const std::string dir = config.configDir.empty() ? dataPath("config") : config.configDir;
  ProviderMap providers = loadProviders(dir + "/camera_modules.json");
  if (!config.providers.empty()) overrideProviders(providers, config.providers, "CameraPipelineConfig.providers");
  ModuleContext context;
  context.configDir = dir;  // the modules' parameters/ beside camera_modules.json
  context.headId = config.headId;
  context.params = config.params;
  context.debug = debug_ = config.debug;
  pipeline_.setDebug(config.debug, std::string("vision_") + cameraName(camera));
  board_.write<VisionGeometry>() = geometry_;
  pipeline_.inputs<CameraImage, CameraMatrix, VisionGeometry, OwnBody>();
  for (const std::string& name : chosenModules(providers)) {
    std::unique_ptr<ModuleBase> module = createModule(name, context);
    if (module->cadence() != Cadence::Cognition)
      throw Error(dir + "/camera_modules.json",
                  "module " + name + " does not run once per image (cadence " + cadenceName(module->cadence()) + ")");
    pipeline_.add(std::move(module));
  }
  pipeline_.sort();
  percepts_.camera = camera_;
}

const CameraPercepts& CameraPipeline::process(const CameraImage& image, const CameraMatrix& cm, const OwnBody& body) {
  if (image.camera != camera_)
    throw Error("camera pipeline", std::string("an image of the ") + cameraName(image.camera) +
                                       " camera given to the " + cameraName(camera_) + " camera's pipeline");
  const Clock::time_point start = Clock::now();
  moduleMs_.clear();
  if (!image.valid()) {
    processed_ = false;
    percepts_ = CameraPercepts{};
    percepts_.camera = camera_;
    percepts_.timestamp = image.timestamp;
    percepts_.cameraMatrix = cm;
    totalMs_ = 0;
    return percepts_;
  }
  if (debug_) debug_->setTime(image.timestamp);
  board_.write<CameraImage>() = image;
  board_.write<CameraMatrix>() = cm;
  board_.write<OwnBody>() = body;
  Clock::time_point last = Clock::now();
  for (const auto& module : pipeline_.modules()) {
    module->execute(board_);
    const Clock::time_point now = Clock::now();
    moduleMs_.push_back({module->name(), msBetween(last, now)});
    last = now;
  }
  if (pipeline_.timing()) {
    std::vector<double> ms;
    for (const ModuleTime& t : moduleMs_) ms.push_back(t.ms);
    pipeline_.writeTiming(ms);
  }
  processed_ = true;
  percepts_ = board_.read<CameraPercepts>();
  totalMs_ = msBetween(start, Clock::now());
  return percepts_;
}

VisionResult CameraPipeline::visionResult() const {
  VisionResult r;
  if (!processed_) return r;
  r.regions = board_.read<ScanLineRegions>();
  r.boundary = percepts_.fieldBoundary;
  r.obstacles = percepts_.obstacles;
  r.lines = percepts_.linesPercept();
  r.ball = percepts_.ball;
  r.penaltyMarkImage = percepts_.penaltyMarkImage;
  for (const ModuleTime& t : moduleMs_) r.stageMs[t.module] = t.ms;
  r.stageMs["total"] = totalMs_;
  return r;
}

}  // namespace nao
