#pragma once
// The colour-segmented scan-line regions of the image, classified with this image's own
// field colour and white point (perception/vision/ScanLineRegionizer.h), not yet cut at the
// field boundary. A noisy image is read blurred (ImageDenoiser): noise breaks regions apart.
// A module of the camera pipeline (perception/vision/CameraPipeline.h), once per image.
#include "perception/vision/ScanGrid.h"
#include "representations/perception/DenoisedImage.h"
#include "representations/perception/UncutScanLineRegions.h"
#include "robot/CameraImage.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class ScanLineRegionProvider : public Module<ScanLineRegionProvider, Requires<CameraImage, DenoisedImage, ScanGrid>,
                                             Provides<UncutScanLineRegions>, Cadence::Cognition> {
 public:
  explicit ScanLineRegionProvider(const ModuleContext& context = {});

 private:
  void update() override;
};

}  // namespace nao::modules
