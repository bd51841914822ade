#include "perception/vision/modules/ImageDenoiser.h"

#include "robot/ModuleRegistry.h"

namespace nao::modules {

ImageDenoiser::ImageDenoiser(const ModuleContext& context) : params_(context.load<DenoiseParams>(name())) {}

void ImageDenoiser::update() {
  const CameraImage& image = in<CameraImage>();
  DenoisedImage& out = this->out<DenoisedImage>();
  out.noise = lumaNoise(image, params_.sampleStep);
  out.radius = params_.enabled && out.noise > params_.minNoise ? params_.radius : 0;
  if (out.radius > 0) boxBlur(image, out.radius, out.blurred);
}

NAO_REGISTER_MODULE(ImageDenoiser);

}  // namespace nao::modules
