#include "perception/vision/modules/PenaltyMarkPerceptor.h"

#include "perception/vision/PenaltyMarkDetector.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

PenaltyMarkPerceptor::PenaltyMarkPerceptor(const ModuleContext&) {}

void PenaltyMarkPerceptor::update() {
  vision::PenaltyMarkParams params;
  params.size = in<VisionGeometry>().penaltyCrossSize;
  PenaltyMarkPercept& mark = out<PenaltyMarkPercept>();
  mark.image = Eigen::Vector2d::Zero();
  mark.position = vision::detectPenaltyMark(in<CameraImage>(), in<ScanLineRegions>(), in<FieldColourReference>(),
                                            in<FieldLines>().lines, in<ObstaclesPercept>(), in<CameraMatrix>(), params,
                                            &mark.image, &in<BallPercept>());
}

NAO_REGISTER_MODULE(PenaltyMarkPerceptor);

}  // namespace nao::modules
