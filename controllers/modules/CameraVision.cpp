#include "controllers/modules/CameraVision.h"

#include "controllers/modules/ModuleField.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

namespace {

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
  config.debug = context.debug;
  for (CameraId cam : {CameraId::Top, CameraId::Bottom})
    pipelines_[static_cast<int>(cam)] = std::make_unique<CameraPipeline>(cam, geometry, config);
}

void CameraVision::update() {
  const CameraImage& image = in<CurrentImage>().image;
  const ImageCameraMatrix& m = in<ImageCameraMatrix>();
  CameraPercepts& out = this->out<CameraPercepts>();
  if (!m.valid || !image.valid() || m.camera != image.camera) {
    // Nothing seen (no motion cycle yet, or an empty image): still this image's percept set.
    out = CameraPercepts{};
    out.camera = image.camera;
    out.timestamp = image.timestamp;
    return;
  }
  out = pipelines_[static_cast<int>(image.camera)]->process(image, m.matrix);
}

NAO_REGISTER_MODULE(CameraVision);

}  // namespace nao::modules
