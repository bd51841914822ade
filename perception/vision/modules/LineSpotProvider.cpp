#include "perception/vision/modules/LineSpotProvider.h"

#include "perception/vision/LineDetector.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

LineSpotProvider::LineSpotProvider(const ModuleContext&) {}

void LineSpotProvider::update() {
  const VisionGeometry& geometry = in<VisionGeometry>();
  vision::LineParams params;
  params.lineWidth = geometry.lineWidth;
  params.circleRadius = geometry.circleRadius;
  static_cast<vision::LineCandidates&>(out<LineSpots>()) =
      vision::findLineCandidates(in<DenoisedImage>().image(in<CameraImage>()), in<ScanLineRegions>(), in<FieldColourReference>(),
                                 in<ObstaclesPercept>(), in<CameraMatrix>(), params, &in<BallPercept>());
}

NAO_REGISTER_MODULE(LineSpotProvider);

}  // namespace nao::modules
