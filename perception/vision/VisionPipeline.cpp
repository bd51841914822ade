#include "perception/vision/VisionPipeline.h"

#include <memory>

#include "perception/vision/CameraPipeline.h"

namespace nao {

VisionResult runVision(const CameraImage& image, const CameraMatrix& cm) {
  return runVision(image, cm, VisionGeometry{});
}

VisionResult runVision(const CameraImage& image, const CameraMatrix& cm, const VisionGeometry& geometry) {
  if (!image.valid()) return {};
  // One camera pipeline per camera and thread, built again only when the geometry changes
  // (building one reads config/camera_modules.json).
  thread_local std::unique_ptr<CameraPipeline> pipelines[kNumCameras];
  std::unique_ptr<CameraPipeline>& pipeline = pipelines[static_cast<int>(image.camera)];
  const auto same = [](const VisionGeometry& a, const VisionGeometry& b) {
    return a.lineWidth == b.lineWidth && a.circleRadius == b.circleRadius && a.penaltyCrossSize == b.penaltyCrossSize &&
           a.ballRadius == b.ballRadius;
  };
  if (!pipeline || !same(pipeline->geometry(), geometry))
    pipeline = std::make_unique<CameraPipeline>(image.camera, geometry);
  pipeline->process(image, cm);
  return pipeline->visionResult();
}

}  // namespace nao
