#include "perception/vision/VisionPipeline.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "perception/vision/BallClassifier.h"
#include "perception/vision/BallDetector.h"
#include "perception/vision/CircleDetector.h"
#include "perception/vision/FieldBoundaryDetector.h"
#include "perception/vision/GoalBoxDetector.h"
#include "perception/vision/IntersectionDetector.h"
#include "perception/vision/LineDetector.h"
#include "perception/vision/ObstacleDetector.h"
#include "perception/vision/PenaltyMarkDetector.h"
#include "perception/vision/ScanGrid.h"
#include "perception/vision/ScanLineRegionizer.h"

namespace nao {

VisionGeometry VisionGeometry::from(const FieldDimensions& d) {
  VisionGeometry g;
  g.lineWidth = d.lineWidth;
  g.circleRadius = FieldModel::from(d).centerCircleRadius;
  g.penaltyCrossSize = d.penaltyCrossSize;
  return g;
}

VisionResult runVision(const CameraImage& image, const CameraMatrix& cm) { return runVision(image, cm, VisionGeometry{}); }

namespace {

class StageClock {
 public:
  explicit StageClock(std::map<std::string, double>& out) : out_(out), start_(now()), last_(start_) {}
  void stage(const char* name) {
    const auto t = now();
    out_[name] = ms(last_, t);
    last_ = t;
  }
  void total() { out_["total"] = ms(start_, now()); }

 private:
  using Clock = std::chrono::steady_clock;
  static Clock::time_point now() { return Clock::now(); }
  static double ms(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  }
  std::map<std::string, double>& out_;
  Clock::time_point start_, last_;
};

}  // namespace

VisionResult runVision(const CameraImage& image, const CameraMatrix& cm, const VisionGeometry& geometry) {
  VisionResult r;
  if (!image.valid()) return r;
  StageClock clock(r.stageMs);
  const ScanGrid grid = makeScanGrid(cm, image.width, image.height, geometry.lineWidth);
  clock.stage("scan_grid");
  const ScanLineRegions all = computeScanLineRegions(image, grid, nullptr);
  clock.stage("scan_line_regions");
  r.boundary = detectFieldBoundary(image, all, cm);
  r.regions = cutAtBoundary(all, r.boundary);
  clock.stage("field_boundary");
  r.obstacles = detectObstacles(image, r.regions, r.boundary, cm);
  clock.stage("obstacles");

  vision::BallParams ballParams;
  ballParams.radius = geometry.ballRadius;
  ballParams.classifier = &vision::defaultBallClassifier();
  const vision::FieldReference field = vision::FieldReference::from(r.regions);
  r.ball = vision::detectBall(image, r.regions, field, r.obstacles, cm, ballParams);
  clock.stage("ball");

  vision::LineParams lineParams;
  lineParams.lineWidth = geometry.lineWidth;
  lineParams.circleRadius = geometry.circleRadius;
  const vision::LineCandidates candidates =
      vision::findLineCandidates(image, r.regions, field, r.obstacles, cm, lineParams, &r.ball);
  clock.stage("line_spots");
  vision::CircleParams circleParams;
  circleParams.radius = geometry.circleRadius;
  circleParams.lineWidth = geometry.lineWidth;
  std::vector<char> onCircle;
  r.lines.circle = vision::detectCircle(candidates, image, field, r.obstacles, cm, circleParams, &onCircle);
  clock.stage("circle");
  // Debugging aid (NAO_LINEDEBUG=1): why each line candidate was dropped. Read once, not per frame.
  static const bool lineDebug = std::getenv("NAO_LINEDEBUG") != nullptr;
  std::vector<vision::RejectedLine> rejected;
  r.lines.lines =
      vision::fitLines(candidates, onCircle, image, field, r.obstacles, cm, lineParams, lineDebug ? &rejected : nullptr);
  if (lineDebug)
    for (const auto& x : rejected)
      std::fprintf(stderr, "REJECT (%.0f,%.0f)-(%.0f,%.0f) spots %d %s %.3f\n", x.imageFrom.x(), x.imageFrom.y(),
                   x.imageTo.x(), x.imageTo.y(), x.spots, x.reason, x.value);
  clock.stage("lines");
  r.lines.intersections = vision::detectIntersections(r.lines.lines, cm, r.obstacles, {}, &image, &field);
  vision::PenaltyMarkParams penaltyParams;
  penaltyParams.size = geometry.penaltyCrossSize;
  r.lines.penaltyMark = vision::detectPenaltyMark(image, r.regions, field, r.lines.lines, r.obstacles, cm, penaltyParams,
                                                  &r.penaltyMarkImage, &r.ball);
  r.lines.goalBoxSide = vision::detectGoalBoxSide(r.lines.lines, image.width, image.height, vision::GoalBoxParams{});
  clock.stage("intersections_marks");
  clock.total();
  return r;
}

}  // namespace nao
