#include "perception/vision/modules/FieldBoundaryProvider.h"

#include "perception/vision/FieldBoundaryDetector.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

FieldBoundaryProvider::FieldBoundaryProvider(const ModuleContext&) {}

void FieldBoundaryProvider::update() {
  out<FieldBoundary>() = detectFieldBoundary(in<CameraImage>(), in<UncutScanLineRegions>(), in<CameraMatrix>());
}

NAO_REGISTER_MODULE(FieldBoundaryProvider);

}  // namespace nao::modules
