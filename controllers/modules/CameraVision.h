#pragma once
// Cognition: the current image through its camera's vision (perception/vision/CameraPipeline.h:
// the same modules for both cameras, each camera with its own pipeline and blackboard, as
// B-Human's Upper and Lower threads), with the camera matrix and the robot's own body at the
// image's exposure time.
// Publishes the image's CameraPercepts for modeling and behaviour.
#include <array>
#include <memory>

#include "perception/OwnBody.h"
#include "perception/vision/CameraPipeline.h"
#include "representations/infrastructure/CurrentImage.h"
#include "representations/perception/CameraPercepts.h"
#include "representations/perception/ImageCameraMatrix.h"
#include "representations/perception/VisionGeometry.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class CameraVision : public Module<CameraVision, Requires<CurrentImage, ImageCameraMatrix, OwnBody>, Provides<CameraPercepts>,
                                   Cadence::Cognition> {
 public:
  // The painted sizes: context.params["CameraVision"] (a VisionGeometry, e.g. from the run's
  // field file), else the field file in the configuration folder.
  explicit CameraVision(const ModuleContext& context = {});
  const CameraPipeline& pipeline(CameraId camera) const { return *pipelines_[static_cast<int>(camera)]; }

 private:
  void update() override;

  std::array<std::unique_ptr<CameraPipeline>, kNumCameras> pipelines_;
};

}  // namespace nao::modules
