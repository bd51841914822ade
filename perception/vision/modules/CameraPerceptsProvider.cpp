#include "perception/vision/modules/CameraPerceptsProvider.h"

#include "robot/ModuleRegistry.h"

namespace nao::modules {

CameraPerceptsProvider::CameraPerceptsProvider(const ModuleContext&) {}

void CameraPerceptsProvider::update() {
  const CameraImage& image = in<CameraImage>();
  CameraPercepts& p = out<CameraPercepts>();
  p.camera = image.camera;
  p.timestamp = image.timestamp;
  p.cameraMatrix = in<CameraMatrix>();
  p.processed = true;
  p.lines = in<FieldLines>().lines;
  p.intersections = in<IntersectionsPercept>().intersections;
  p.circle = in<CirclePercept>().circle;
  p.penaltyMark = in<PenaltyMarkPercept>().position;
  p.penaltyMarkImage = in<PenaltyMarkPercept>().image;
  p.goalBoxSide = in<GoalBoxSidePercept>().side;
  p.ball = in<BallPercept>();
  p.obstacles = in<ObstaclesPercept>();
  p.fieldBoundary = in<FieldBoundary>();
}

NAO_REGISTER_MODULE(CameraPerceptsProvider);

}  // namespace nao::modules
