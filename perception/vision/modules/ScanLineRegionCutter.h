#pragma once
// The scan-line regions below the field boundary (cutAtBoundary): what every later stage
// looks at.
// A module of the camera pipeline (perception/vision/CameraPipeline.h), once per image.
#include "perception/vision/VisionTypes.h"
#include "representations/perception/UncutScanLineRegions.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class ScanLineRegionCutter : public Module<ScanLineRegionCutter, Requires<UncutScanLineRegions, FieldBoundary>,
                                           Provides<ScanLineRegions>, Cadence::Cognition> {
 public:
  explicit ScanLineRegionCutter(const ModuleContext& context = {});

 private:
  void update() override;
};

}  // namespace nao::modules
