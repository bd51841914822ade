#pragma once
// The scan-line regions of one image down from the horizon, before the field boundary cuts
// them (ScanLineRegionProvider); the field boundary is found from these.
#include "perception/vision/VisionTypes.h"

namespace nao {

struct UncutScanLineRegions : ScanLineRegions {};

}  // namespace nao
