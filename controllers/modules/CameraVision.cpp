#include "controllers/modules/CameraVision.h"

#include "controllers/modules/ModuleField.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

namespace {

NAO_DEBUG_CHANNEL(kVisionSkips, "vision_skips", "images the vision did not process, with the reason (no camera matrix, no pixels, an implausible camera matrix)");

// A camera matrix no standing or walking NAO can have (a bad joint reading, a broken
// calibration): the percepts from it would be garbage for every model downstream.
std::string implausible(const CameraMatrix& m) {
  const Eigen::Matrix3d r = m.pose.linear();
  if (!r.allFinite() || !m.pose.translation().allFinite()) return "camera matrix not finite";
  if ((r.transpose() * r - Eigen::Matrix3d::Identity()).norm() > 1e-3) return "camera rotation not orthonormal";
  const double z = m.pose.translation().z();
  if (z < 0.15 || z > 1.0) return "camera " + std::to_string(z) + " m above the ground";
  return {};
}

VisionGeometry geometryFor(const ModuleContext& context) {
  if (auto it = context.params.find("CameraVision"); it != context.params.end())
    if (const auto* g = std::any_cast<VisionGeometry>(&it->second)) return *g;
  return VisionGeometry::from(fieldFor(context));
}

}  // namespace

CameraVision::CameraVision(const ModuleContext& context) {
  const VisionGeometry geometry = geometryFor(context);
  CameraPipelineConfig config;
  config.configDir = context.configDir;
  config.headId = context.headId;
  config.params = context.params;  // a scenario's or test's parameters for the vision's modules
  config.debug = context.debug;
  for (CameraId cam : {CameraId::Top, CameraId::Bottom})
    pipelines_[static_cast<int>(cam)] = std::make_unique<CameraPipeline>(cam, geometry, config);
}

void CameraVision::update() {
  const CameraImage& image = in<CurrentImage>().image;
  const ImageCameraMatrix& m = in<ImageCameraMatrix>();
  CameraPercepts& out = this->out<CameraPercepts>();
  std::string problem = !m.valid || m.camera != image.camera ? "no camera matrix for the image's time"
                        : !image.valid()                     ? "no pixels"
                                                             : implausible(m.matrix);
  if (!problem.empty()) {
    // Nothing seen: still this image's percept set, marked not processed.
    debug(kVisionSkips, [&] { return nlohmann::json{{"camera", cameraName(image.camera)}, {"reason", problem}}; });
    out = CameraPercepts{};
    out.camera = image.camera;
    out.timestamp = image.timestamp;
    return;
  }
  out = pipelines_[static_cast<int>(image.camera)]->process(image, m.matrix, in<OwnBody>());
}

NAO_REGISTER_MODULE(CameraVision);

}  // namespace nao::modules
