#include "perception/vision/modules/CirclePerceptor.h"

#include "perception/vision/CircleDetector.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

CirclePerceptor::CirclePerceptor(const ModuleContext&) {}

void CirclePerceptor::update() {
  const VisionGeometry& geometry = in<VisionGeometry>();
  vision::CircleParams params;
  params.radius = geometry.circleRadius;
  params.lineWidth = geometry.lineWidth;
  CirclePercept& circle = out<CirclePercept>();
  circle.spotsOnCircle.clear();
  circle.circle = vision::detectCircle(in<LineSpots>(), in<CameraImage>(), in<FieldColourReference>(),
                                       in<ObstaclesPercept>(), in<CameraMatrix>(), params, &circle.spotsOnCircle);
}

NAO_REGISTER_MODULE(CirclePerceptor);

}  // namespace nao::modules
