#include "controllers/modules/AutoExposureWeighting.h"

#include <cstdlib>

#include "robot/ModuleRegistry.h"
#include "robot/Parameters.h"

namespace nao::modules {

AutoExposureWeighting::AutoExposureWeighting(const ModuleContext& context)
    : params_(context.load<ExposureWeightingParams>(name())) {}

void AutoExposureWeighting::update() {
  const CameraImage& image = in<CurrentImage>().image;
  const ImageCameraMatrix& cm = in<ImageCameraMatrix>();
  // Until the camera matrix is known, the camera keeps metering its whole image.
  if (image.valid() && cm.valid && cm.camera == image.camera) {
    const ExposureWeights next = exposureWeights(cm.matrix, in<OwnBody>(), params_);
    ExposureWeights& current = weights_.camera[static_cast<int>(image.camera)];
    int change = 0;
    for (std::size_t k = 0; k < next.cell.size(); ++k) change += std::abs(next.cell[k] - current.cell[k]);
    if (change > 0 && change >= params_.minChange) current = next;
  }
  out<AutoExposureWeights>() = weights_;
}

NAO_REGISTER_MODULE(AutoExposureWeighting);

}  // namespace nao::modules
