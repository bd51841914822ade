#include "perception/vision/modules/LinePerceptor.h"

#include <cstdio>
#include <cstdlib>

#include "perception/vision/LineDetector.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

LinePerceptor::LinePerceptor(const ModuleContext&) {}

void LinePerceptor::update() {
  const VisionGeometry& geometry = in<VisionGeometry>();
  vision::LineParams params;
  params.lineWidth = geometry.lineWidth;
  params.circleRadius = geometry.circleRadius;
  // Debugging aid (NAO_LINEDEBUG=1): why each line candidate was dropped. Read once, not per frame.
  static const bool lineDebug = std::getenv("NAO_LINEDEBUG") != nullptr;
  std::vector<vision::RejectedLine> rejected;
  out<FieldLines>().lines = vision::fitLines(in<LineSpots>(), in<CirclePercept>().spotsOnCircle, in<CameraImage>(),
                                             in<FieldColourReference>(), in<ObstaclesPercept>(), in<CameraMatrix>(),
                                             params, lineDebug ? &rejected : nullptr);
  if (lineDebug)
    for (const auto& x : rejected)
      std::fprintf(stderr, "REJECT (%.0f,%.0f)-(%.0f,%.0f) spots %d %s %.3f\n", x.imageFrom.x(), x.imageFrom.y(),
                   x.imageTo.x(), x.imageTo.y(), x.spots, x.reason, x.value);
}

NAO_REGISTER_MODULE(LinePerceptor);

}  // namespace nao::modules
