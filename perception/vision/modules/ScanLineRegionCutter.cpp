#include "perception/vision/modules/ScanLineRegionCutter.h"

#include "perception/vision/ScanLineRegionizer.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

ScanLineRegionCutter::ScanLineRegionCutter(const ModuleContext&) {}

void ScanLineRegionCutter::update() {
  out<ScanLineRegions>() = cutAtBoundary(in<UncutScanLineRegions>(), in<FieldBoundary>());
}

NAO_REGISTER_MODULE(ScanLineRegionCutter);

}  // namespace nao::modules
