#include "perception/vision/modules/LinePerceptor.h"

#include "perception/vision/LineDetector.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

NAO_DEBUG_CHANNEL(kLineRejects, "line_rejects",
                  "each line candidate the line fit dropped: image end points, spots, the failed test and its value");

LinePerceptor::LinePerceptor(const ModuleContext&) {}

void LinePerceptor::update() {
  const VisionGeometry& geometry = in<VisionGeometry>();
  vision::LineParams params;
  params.lineWidth = geometry.lineWidth;
  params.circleRadius = geometry.circleRadius;
  const bool rejects = debugging(kLineRejects);
  std::vector<vision::RejectedLine> rejected;
  out<FieldLines>().lines = vision::fitLines(in<LineSpots>(), in<CirclePercept>().spotsOnCircle, in<CameraImage>(),
                                             in<FieldColourReference>(), in<ObstaclesPercept>(), in<CameraMatrix>(),
                                             params, rejects ? &rejected : nullptr);
  for (const auto& x : rejected)
    debug(kLineRejects, [&] {
      return nlohmann::json{{"camera", cameraName(in<CameraImage>().camera)},
                            {"image", {{x.imageFrom.x(), x.imageFrom.y()}, {x.imageTo.x(), x.imageTo.y()}}},
                            {"spots", x.spots},
                            {"reason", x.reason},
                            {"value", x.value}};
    });
}

NAO_REGISTER_MODULE(LinePerceptor);

}  // namespace nao::modules
