#pragma once
// Cognition cadence: the auto exposure weights of the current image's camera
// (perception/ExposureWeighting.h): the near ground, not the own body, not the hall above the
// horizon. The next images of that camera are exposed for the field the vision reads.
#include "perception/ExposureWeighting.h"
#include "perception/OwnBody.h"
#include "representations/infrastructure/AutoExposureWeights.h"
#include "representations/infrastructure/CurrentImage.h"
#include "representations/perception/ImageCameraMatrix.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class AutoExposureWeighting : public Module<AutoExposureWeighting, Requires<CurrentImage, ImageCameraMatrix, OwnBody>,
                                            Provides<AutoExposureWeights>, Cadence::Cognition> {
 public:
  // Parameters: config/parameters/AutoExposureWeighting.json (ExposureWeightingParams).
  explicit AutoExposureWeighting(const ModuleContext& context = {});

 private:
  void update() override;
  ExposureWeightingParams params_;
  AutoExposureWeights weights_;
};

}  // namespace nao::modules
