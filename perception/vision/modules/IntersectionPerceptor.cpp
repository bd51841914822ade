#include "perception/vision/modules/IntersectionPerceptor.h"

#include "perception/vision/IntersectionDetector.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

IntersectionPerceptor::IntersectionPerceptor(const ModuleContext&) {}

void IntersectionPerceptor::update() {
  out<IntersectionsPercept>().intersections =
      vision::detectIntersections(in<FieldLines>().lines, in<CameraMatrix>(), in<ObstaclesPercept>(), {},
                                  &in<CameraImage>(), &in<FieldColourReference>());
}

NAO_REGISTER_MODULE(IntersectionPerceptor);

}  // namespace nao::modules
