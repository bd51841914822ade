#include "perception/vision/modules/BallPerceptor.h"

#include "perception/vision/BallClassifier.h"
#include "perception/vision/BallDetector.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

BallPerceptor::BallPerceptor(const ModuleContext&) {}

void BallPerceptor::update() {
  vision::BallParams params;
  params.radius = in<VisionGeometry>().ballRadius;
  params.classifier = &vision::defaultBallClassifier();
  params.ownBody = &in<OwnBody>();
  out<BallPercept>() = vision::detectBall(in<DenoisedImage>().image(in<CameraImage>()), in<ScanLineRegions>(), in<FieldColourReference>(),
                                          in<ObstaclesPercept>(), in<CameraMatrix>(), params);
}

NAO_REGISTER_MODULE(BallPerceptor);

}  // namespace nao::modules
