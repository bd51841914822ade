#include "perception/vision/modules/ObstaclePerceptor.h"

#include "perception/vision/ObstacleDetector.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

ObstaclePerceptor::ObstaclePerceptor(const ModuleContext&) {}

void ObstaclePerceptor::update() {
  out<ObstaclesPercept>() =
      detectObstacles(in<CameraImage>(), in<ScanLineRegions>(), in<FieldBoundary>(), in<CameraMatrix>());
}

NAO_REGISTER_MODULE(ObstaclePerceptor);

}  // namespace nao::modules
