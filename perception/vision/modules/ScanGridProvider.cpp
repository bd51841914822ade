#include "perception/vision/modules/ScanGridProvider.h"

#include "perception/vision/ScanGrid.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

ScanGridProvider::ScanGridProvider(const ModuleContext&) {}

void ScanGridProvider::update() {
  const CameraImage& image = in<CameraImage>();
  out<ScanGrid>() = makeScanGrid(in<CameraMatrix>(), image.width, image.height, in<VisionGeometry>().lineWidth);
}

NAO_REGISTER_MODULE(ScanGridProvider);

}  // namespace nao::modules
