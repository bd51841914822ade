#include "perception/vision/modules/ScanLineRegionProvider.h"

#include "perception/vision/ScanLineRegionizer.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

ScanLineRegionProvider::ScanLineRegionProvider(const ModuleContext&) {}

void ScanLineRegionProvider::update() {
  static_cast<ScanLineRegions&>(out<UncutScanLineRegions>()) =
      computeScanLineRegions(in<DenoisedImage>().image(in<CameraImage>()), in<ScanGrid>(), nullptr);
}

NAO_REGISTER_MODULE(ScanLineRegionProvider);

}  // namespace nao::modules
