#pragma once
// This image's sensor noise and, where it is high, a blurred copy for the scan-line regions and
// the ball (perception/vision/Denoise.h).
// A module of the camera pipeline (perception/vision/CameraPipeline.h), once per image.
#include "perception/vision/Denoise.h"
#include "representations/perception/DenoisedImage.h"
#include "robot/CameraImage.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class ImageDenoiser
    : public Module<ImageDenoiser, Requires<CameraImage>, Provides<DenoisedImage>, Cadence::Cognition> {
 public:
  // Parameters: config/parameters/ImageDenoiser.json (DenoiseParams).
  explicit ImageDenoiser(const ModuleContext& context = {});

 private:
  void update() override;
  DenoiseParams params_;
};

}  // namespace nao::modules
