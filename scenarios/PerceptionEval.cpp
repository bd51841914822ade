#include "scenarios/PerceptionEval.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <deque>
#include <cmath>
#include <memory>
#include <optional>
#include <random>

#include "controllers/StandController.h"
#include "perception/CameraModel.h"
#include "perception/Geometry.h"
#include "perception/vision/Annotate.h"
#include "perception/vision/CameraPipeline.h"
#include "perception/vision/VisionPipeline.h"
#include "representations/perception/DenoisedImage.h"
#include "robot/Error.h"
#include "robot/OutputFiles.h"
#include "robot/ForwardKinematics.h"
#include "robot/Paths.h"
#include "sim/CameraRenderer.h"
#include "sim/GroundTruth.h"
#include "sim/ImageIO.h"
#include "sim/OracleCamera.h"
#include "sim/SceneBuilder.h"
#include "sim/World.h"
#include "scenarios/ProgramMetering.h"
#include "scenarios/RandomView.h"

namespace nao::sim {

NAO_DEBUG_CHANNEL(kEvalLines, "eval_lines",
                  "eval perception: each true line in view the vision missed and each detected line matching no "
                  "field line, with the trial, lighting, camera and where it lies");
NAO_DEBUG_CHANNEL(kEvalBalls, "eval_balls",
                  "eval perception: each ball percept, where it puts the ball on the field and whether a real ball "
                  "lies there");

namespace {

constexpr double kDeg = M_PI / 180;
constexpr double kLineMaxAngle = 5 * kDeg;
constexpr double kLineMaxDist = 0.10;

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

double pointLineDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& dir) {
  const Eigen::Vector2d r = p - a;
  return std::abs(r.x() * dir.y() - r.y() * dir.x());
}

// Does a detected segment (field frame) lie on a true line: within 5 deg of its direction,
// both ends within 10 cm of it, overlapping its extent?
bool lineMatches(const Eigen::Vector2d& d0, const Eigen::Vector2d& d1, const Eigen::Vector2d& t0,
                 const Eigen::Vector2d& t1) {
  const double lt = (t1 - t0).norm(), ld = (d1 - d0).norm();
  if (lt < 1e-9 || ld < 1e-9) return false;
  const Eigen::Vector2d ut = (t1 - t0) / lt, ud = (d1 - d0) / ld;
  if (std::abs(ut.x() * ud.y() - ut.y() * ud.x()) > std::sin(kLineMaxAngle)) return false;
  if (pointLineDistance(d0, t0, ut) > kLineMaxDist || pointLineDistance(d1, t0, ut) > kLineMaxDist) return false;
  const double a = (d0 - t0).dot(ut), b = (d1 - t0).dot(ut);
  return std::max(a, b) > -kLineMaxDist && std::min(a, b) < lt + kLineMaxDist;
}

FieldIntersection::Type truthType(LinesPercept::Intersection::Type t) {
  switch (t) {
    case LinesPercept::Intersection::Type::L: return FieldIntersection::Type::L;
    case LinesPercept::Intersection::Type::T: return FieldIntersection::Type::T;
    default: return FieldIntersection::Type::X;
  }
}

// Truth that is the same under every lighting: what one camera sees of one scene.
struct FrameTruth {
  std::vector<VisibleLine> lines;  // >= 0.5 m visible within 4 m
  bool circleEligible = false;     // >= half of the circle in view within 3 m
  std::vector<VisibleBall> balls3, balls5;
  bool penaltyMarkEligible = false;  // a penalty cross in view within 3 m, wholly in the image
};

FrameTruth computeTruth(const World& world, CameraId camera) {
  FrameTruth t;
  const VisibleFeatures v4 = visibleFeatures(world, 0, camera, 4.0);
  for (const auto& l : v4.lines) {
    if (l.visibleLength < 0.5) continue;  // clipping only shortens the stretch
    // Clipped exactly at the image border: the paint's whole width must be in the image.
    if (const auto c = visibleStretch(world, 0, camera, l.index, 4.0, true); c && c->visibleLength >= 0.5)
      t.lines.push_back(*c);
  }
  // The circle within 3 m.
  const FieldModel& f = world.field();
  int visible = 0;
  constexpr int kSamples = 90;
  for (int k = 0; k < kSamples; ++k) {
    const double a = 2 * M_PI * k / kSamples;
    const Eigen::Vector2d p = f.centerCircleCenter + f.centerCircleRadius * Eigen::Vector2d(std::cos(a), std::sin(a));
    visible += trulyVisible(world, 0, camera, Eigen::Vector3d(p.x(), p.y(), 0.001), 3.0);
  }
  t.circleEligible = visible * 2 >= kSamples;
  // The penalty cross: its centre truly visible within 3 m and its four arm ends in the image.
  std::optional<Eigen::Vector2d> cross;
  for (const auto& c : f.penaltyCrosses)
    if (trulyVisible(world, 0, camera, Eigen::Vector3d(c.x(), c.y(), 0.001), 3.0)) cross = c;
  if (const auto& c = cross) {
    const CameraResolution r = world.cameraResolution(camera);
    bool whole = true;
    for (const Eigen::Vector2d& d : {Eigen::Vector2d(0.05, 0), Eigen::Vector2d(-0.05, 0), Eigen::Vector2d(0, 0.05),
                                    Eigen::Vector2d(0, -0.05)}) {
      const auto px = truePixel(world, 0, camera, Eigen::Vector3d(c->x() + d.x(), c->y() + d.y(), 0.001));
      whole = whole && px && px->x() >= 0 && px->y() >= 0 && px->x() < r.width && px->y() < r.height;
    }
    t.penaltyMarkEligible = whole;
  }
  // Balls: in view (not hidden) with at least 75 % of the disc on the image.
  const CameraResolution res = world.cameraResolution(camera);
  const VisibleFeatures vb = visibleFeatures(world, 0, camera, 5.0);
  for (const auto& b : vb.balls) {
    if (discInImage(b.image, b.radiusPx, res.width, res.height) < 0.75) continue;
    if (b.distance <= 5.0) t.balls5.push_back(b);
    if (b.distance <= 3.0) t.balls3.push_back(b);
  }
  return t;
}

// What the eval_lines and eval_balls lines name besides the camera.
struct FrameLabel {
  DebugChannels& debug;
  int trial;
  const std::string& lighting;
};

void scoreFrame(const World& world, CameraId camera, const FrameTruth& truth, const VisionResult& r,
                const Eigen::Vector3d& robotPose, PerceptionFigures& fig, const FrameLabel& label) {
  DebugChannels& debug = label.debug;
  ++fig.frames;
  const FieldModel& field = world.field();
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> detected;
  for (const auto& l : r.lines.lines) detected.emplace_back(robotToField(l.from, robotPose), robotToField(l.to, robotPose));
  // Recall over the true lines in view.
  for (const auto& tl : truth.lines) {
    ++fig.trueLines;
    const FieldLine& fl = field.lines[tl.index];
    bool ok = false;
    for (const auto& d : detected)
      if (lineMatches(d.first, d.second, fl.from, fl.to)) {
        ++fig.trueLinesFound;
        ok = true;
        break;
      }
    if (!ok && debug.on(kEvalLines)) {
      const Eigen::Vector2d cam = world.cameraPose(0, camera).translation().head<2>();
      const Eigen::Vector2d u = (tl.to - tl.from).normalized();
      const double t = std::clamp((cam - tl.from).dot(u), 0.0, tl.visibleLength);
      debug.write(kEvalLines, {{"kind", "miss"},
                               {"trial", label.trial},
                               {"lighting", label.lighting},
                               {"camera", cameraName(camera)},
                               {"line", tl.name},
                               {"visible_m", tl.visibleLength},
                               {"nearest_m", (tl.from + t * u - cam).norm()},
                               {"image", {{tl.imageFrom.x(), tl.imageFrom.y()}, {tl.imageTo.x(), tl.imageTo.y()}}}});
    }
  }
  // Precision over every detection, against every line of the field.
  for (std::size_t di = 0; di < detected.size(); ++di) {
    const auto& d = detected[di];
    ++fig.detectedLines;
    bool ok = false;
    for (const auto& fl : field.lines)
      if (lineMatches(d.first, d.second, fl.from, fl.to)) {
        ++fig.detectedLinesMatched;
        ok = true;
        break;
      }
    if (!ok && debug.on(kEvalLines)) {
      double bestA = 1e9, bestD0 = 0, bestD1 = 0;
      const Eigen::Vector2d ud = (d.second - d.first).normalized();
      for (const auto& fl : field.lines) {
        const Eigen::Vector2d ut = (fl.to - fl.from).normalized();
        const double a = std::asin(std::min(1.0, std::abs(ut.x() * ud.y() - ut.y() * ud.x()))) * 180 / M_PI;
        const double d0 = pointLineDistance(d.first, fl.from, ut), d1 = pointLineDistance(d.second, fl.from, ut);
        if (a + 20 * (d0 + d1) < bestA + 20 * (bestD0 + bestD1)) bestA = a, bestD0 = d0, bestD1 = d1;
      }
      const auto& l = r.lines.lines[di];
      debug.write(kEvalLines, {{"kind", "false"},
                               {"trial", label.trial},
                               {"lighting", label.lighting},
                               {"camera", cameraName(camera)},
                               {"distance_m", std::min(l.from.norm(), l.to.norm())},
                               {"length_m", (l.to - l.from).norm()},
                               {"spots", l.spots.size()},
                               {"nearest_line", {{"angle_deg", bestA}, {"from_m", bestD0}, {"to_m", bestD1}}},
                               {"image", {{l.imageFrom.x(), l.imageFrom.y()}, {l.imageTo.x(), l.imageTo.y()}}}});
    }
  }
  // Circle.
  const bool circleRight =
      r.lines.circle.found && (robotToField(r.lines.circle.centre, robotPose) - field.centerCircleCenter).norm() < 0.3;
  if (truth.circleEligible) {
    ++fig.circleFrames;
    fig.circleFound += circleRight;
  }
  if (r.lines.circle.found && !circleRight) ++fig.circleFalse;
  // Intersections and the penalty mark (informative).
  for (const auto& x : r.lines.intersections) {
    ++fig.intersections;
    const Eigen::Vector2d p = robotToField(x.position, robotPose);
    for (const auto& fx : field.intersections)
      if ((fx.position - p).norm() < 0.3 && fx.type == truthType(x.type)) {
        ++fig.intersectionsCorrect;
        break;
      }
  }
  bool markRight = false;
  if (r.lines.penaltyMark) {
    ++fig.penaltyMarks;
    const Eigen::Vector2d p = robotToField(*r.lines.penaltyMark, robotPose);
    for (const auto& c : field.penaltyCrosses) markRight = markRight || (c - p).norm() < 0.3;
    fig.penaltyMarksCorrect += markRight;
  }
  if (truth.penaltyMarkEligible) {
    ++fig.penaltyMarkFrames;
    fig.penaltyMarkFound += markRight;
  }
  // Ball.
  const Eigen::Vector2d camFoot = world.cameraPose(0, camera).translation().head<2>();
  std::optional<Eigen::Vector2d> seen;
  if (r.ball.seen) {
    ++fig.ballPercepts;
    seen = robotToField(r.ball.position, robotPose);
    bool matchesAny = false;
    for (int b = 0; b < world.ballCount(); ++b) {
      const Eigen::Vector2d tb = world.ballPosition(b).head<2>();
      const double dist = (tb - camFoot).norm();
      if ((*seen - tb).norm() < std::max(0.3, 0.2 * dist)) matchesAny = true;
    }
    fig.falseBalls += !matchesAny;
    debug.emit(kEvalBalls, [&] {
      return nlohmann::json{{"trial", label.trial},
                            {"lighting", label.lighting},
                            {"camera", cameraName(camera)},
                            {"field", {seen->x(), seen->y()}},
                            {"matches_a_ball", matchesAny}};
    });
  }
  auto found = [&](const VisibleBall& b) {
    if (!seen) return false;
    const double err = (*seen - b.position.head<2>()).norm();
    return err < std::max(0.3, 0.2 * b.distance);
  };
  for (const auto& b : truth.balls3) {
    ++fig.balls3;
    fig.found3 += found(b);
  }
  for (const auto& b : truth.balls5) {
    ++fig.balls5;
    if (found(b)) {
      ++fig.found5;
      fig.ballErrorRatios.push_back((*seen - b.position.head<2>()).norm() / std::max(0.05, b.distance));
    }
  }
}

constexpr double kSmallBallPx = 8;  // radius below which a ball's error is fitted in pixels

int binOf(const std::vector<double>& bins, double distance) {
  for (std::size_t i = 0; i < bins.size(); ++i)
    if (distance <= bins[i]) return static_cast<int>(i);
  return -1;
}

// The distance of a pixel from the image line through a and b (pixels).
double acrossPx(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  const double n = d.norm();
  return n < 1e-9 ? (p - a).norm() : std::abs((p - a).x() * d.y() - (p - a).y() * d.x()) / n;
}

// One frame's contribution to the oracle's fit: the oracle's view against what the vision found.
void collectFit(const OracleView& view, const CameraMatrix& cm, const VisionResult& r, const PerceptionFigures& fig,
                const modules::OracleVision::Params& model, OracleFit& fit) {
  ++fit.frames;
  fit.falseBalls += fig.falseBalls;
  fit.falseLines += fig.detectedLines - fig.detectedLinesMatched;
  fit.falseCircles += fig.circleFalse;
  fit.falsePenaltyMarks += fig.penaltyMarks - fig.penaltyMarksCorrect;
  for (const OracleView::Line& l : view.lines) {
    const int bin = binOf(fit.bins, l.distance);
    const auto ta = cm.pixelToGround(l.imageFrom), tb = cm.pixelToGround(l.imageTo);
    if (l.length < model.lines.minLength || bin < 0 || !ta || !tb) continue;
    OracleFit::Rate& rate = l.length >= model.lines.longLength ? fit.linesLong : fit.linesShort;
    ++rate.seen[bin];
    for (const auto& d : r.lines.lines)
      if (lineMatches(d.from, d.to, *ta, *tb)) {
        ++rate.found[bin];
        for (const Eigen::Vector2d& end : {d.from, d.to})
          if (const auto px = cm.projectGround(end)) fit.lineErrorPx.push_back(acrossPx(*px, l.imageFrom, l.imageTo));
        break;
      }
  }
  for (const OracleView::Ball& b : view.balls) {
    const int bin = binOf(fit.bins, b.distance);
    const auto truth = cm.pixelToGround(b.image, kBallRadius);
    if (b.inImage < model.ball.minInImage || bin < 0 || !truth) continue;
    ++fit.ball.seen[bin];
    if (r.ball.seen && (r.ball.position - *truth).norm() < std::max(0.3, 0.2 * b.distance)) {
      ++fit.ball.found[bin];
      const double error = (r.ball.image - b.image).norm();
      if (b.radiusPx >= kSmallBallPx)
        fit.ballErrorPerRadius.push_back(error / b.radiusPx);
      else
        fit.ballErrorPxSmall.push_back(error);
    }
  }
  auto spot = [&](const std::optional<OracleView::Spot>& s, const std::optional<Eigen::Vector2d>& found,
                  OracleFit::Rate& rate, std::vector<double>& errors) {
    if (!s) return;
    const int bin = binOf(fit.bins, s->distance);
    const auto truth = cm.pixelToGround(s->image);
    if (bin < 0 || !truth) return;
    ++rate.seen[bin];
    if (found && (*found - *truth).norm() < 0.3) {
      ++rate.found[bin];
      errors.push_back((*found - *truth).norm());
    }
  };
  spot(view.circleCentre, r.lines.circle.found ? std::optional<Eigen::Vector2d>(r.lines.circle.centre) : std::nullopt,
       fit.circle, fit.circleErrorM);
  spot(view.penaltyMark, r.lines.penaltyMark, fit.penaltyMark, fit.penaltyMarkErrorM);
}

}  // namespace

double PerceptionFigures::medianBallErrorRatio() const { return median(ballErrorRatios); }

OracleFit::OracleFit(std::vector<double> distanceBins) : bins(std::move(distanceBins)) {
  for (Rate* r : {&ball, &linesLong, &linesShort, &circle, &penaltyMark}) {
    r->seen.assign(bins.size(), 0);
    r->found.assign(bins.size(), 0);
  }
}

void OracleFit::add(const OracleFit& o) {
  Rate* mine[] = {&ball, &linesLong, &linesShort, &circle, &penaltyMark};
  const Rate* theirs[] = {&o.ball, &o.linesLong, &o.linesShort, &o.circle, &o.penaltyMark};
  for (int k = 0; k < 5; ++k)
    for (std::size_t i = 0; i < bins.size() && i < theirs[k]->seen.size(); ++i) {
      mine[k]->seen[i] += theirs[k]->seen[i];
      mine[k]->found[i] += theirs[k]->found[i];
    }
  for (auto [to, from] : {std::pair{&ballErrorPerRadius, &o.ballErrorPerRadius},
                          std::pair{&ballErrorPxSmall, &o.ballErrorPxSmall}, std::pair{&lineErrorPx, &o.lineErrorPx},
                          std::pair{&circleErrorM, &o.circleErrorM}, std::pair{&penaltyMarkErrorM, &o.penaltyMarkErrorM}})
    to->insert(to->end(), from->begin(), from->end());
  frames += o.frames, falseBalls += o.falseBalls, falseLines += o.falseLines;
  falseCircles += o.falseCircles, falsePenaltyMarks += o.falsePenaltyMarks;
}

modules::OracleVision::Params OracleFit::params(const modules::OracleVision::Params& defaults,
                                                const std::string& fittedBy) const {
  modules::OracleVision::Params p = defaults;
  p.fittedBy = fittedBy;
  p.distanceBins = bins;
  // A bin without samples takes its nearest sampled neighbour's rate; a table without any keeps
  // the defaults' (where its bins are these), so a small fit never claims "never seen".
  auto rates = [&](const Rate& r, const std::vector<double>& fallback) {
    std::vector<int> sampled;
    for (std::size_t i = 0; i < bins.size(); ++i)
      if (r.seen[i] > 0) sampled.push_back(static_cast<int>(i));
    if (sampled.empty() && fallback.size() == bins.size()) return fallback;
    std::vector<double> out(bins.size(), sampled.empty() ? 1.0 : 0.0);
    for (std::size_t i = 0; i < bins.size() && !sampled.empty(); ++i) {
      int nearest = sampled.front();
      for (int j : sampled)
        if (std::abs(j - static_cast<int>(i)) < std::abs(nearest - static_cast<int>(i))) nearest = j;
      out[i] = static_cast<double>(r.found[nearest]) / r.seen[nearest];
    }
    return out;
  };
  auto perFrame = [&](int n) { return frames ? static_cast<double>(n) / frames : 0.0; };
  // Medians of error magnitudes to sigmas: a 2-D normal's |e| has median 1.1774 sigma, a
  // 1-D one's 0.6745 sigma.
  p.ball.detection = rates(ball, defaults.ball.detection);
  if (!ballErrorPerRadius.empty()) p.ball.sigmaPerRadius = median(ballErrorPerRadius) / 1.1774;
  if (!ballErrorPxSmall.empty()) p.ball.minSigmaPx = median(ballErrorPxSmall) / 1.1774;
  p.ball.falsePerImage = perFrame(falseBalls);
  p.lines.detection = rates(linesLong, defaults.lines.detection);
  p.lines.detectionShort = rates(linesShort, defaults.lines.detectionShort);
  if (!lineErrorPx.empty()) p.lines.sigmaPx = median(lineErrorPx) / 0.6745;
  p.lines.falsePerImage = perFrame(falseLines);
  p.circle.detection = rates(circle, defaults.circle.detection);
  if (!circleErrorM.empty()) p.circle.sigma = median(circleErrorM) / 1.1774;
  p.circle.falsePerImage = perFrame(falseCircles);
  p.penaltyMark.detection = rates(penaltyMark, defaults.penaltyMark.detection);
  if (!penaltyMarkErrorM.empty()) p.penaltyMark.sigma = median(penaltyMarkErrorM) / 1.1774;
  p.penaltyMark.falsePerImage = perFrame(falsePenaltyMarks);
  return p;
}

void PerceptionFigures::add(const PerceptionFigures& o) {
  frames += o.frames;
  trueLines += o.trueLines, trueLinesFound += o.trueLinesFound;
  detectedLines += o.detectedLines, detectedLinesMatched += o.detectedLinesMatched;
  circleFrames += o.circleFrames, circleFound += o.circleFound, circleFalse += o.circleFalse;
  balls3 += o.balls3, found3 += o.found3, balls5 += o.balls5, found5 += o.found5;
  ballPercepts += o.ballPercepts, falseBalls += o.falseBalls;
  ballErrorRatios.insert(ballErrorRatios.end(), o.ballErrorRatios.begin(), o.ballErrorRatios.end());
  intersections += o.intersections, intersectionsCorrect += o.intersectionsCorrect;
  penaltyMarks += o.penaltyMarks, penaltyMarksCorrect += o.penaltyMarksCorrect;
  penaltyMarkFrames += o.penaltyMarkFrames, penaltyMarkFound += o.penaltyMarkFound;
  imageNoise.insert(imageNoise.end(), o.imageNoise.begin(), o.imageNoise.end());
  blurredFrames += o.blurredFrames;
}

nlohmann::json PerceptionFigures::toJson() const {
  return {{"frames", frames},
          {"lines",
           {{"recall", lineRecall()},
            {"precision", linePrecision()},
            {"true_lines", trueLines},
            {"true_lines_found", trueLinesFound},
            {"detections", detectedLines},
            {"detections_matched", detectedLinesMatched}}},
          {"circle",
           {{"detection_rate", circleRate()},
            {"frames_in_view", circleFrames},
            {"found", circleFound},
            {"false_per_frame", frames ? double(circleFalse) / frames : 0.0}}},
          {"ball",
           {{"recall_3m", ballRecall3()},
            {"recall_5m", ballRecall5()},
            {"false_per_frame", falseBallsPerFrame()},
            {"median_error_ratio", medianBallErrorRatio()},
            {"balls_3m", balls3},
            {"balls_5m", balls5},
            {"percepts", ballPercepts},
            {"false", falseBalls}}},
          {"intersections",
           {{"detections", intersections},
            {"precision", intersections ? double(intersectionsCorrect) / intersections : 1.0}}},
          {"penalty_mark",
           {{"detections", penaltyMarks},
            {"precision", penaltyMarks ? double(penaltyMarksCorrect) / penaltyMarks : 1.0},
            {"frames_in_view", penaltyMarkFrames},
            {"recall", penaltyMarkFrames ? double(penaltyMarkFound) / penaltyMarkFrames : 1.0}}},
          {"image", {{"noise_median", median(imageNoise)}, {"blurred_frames", blurredFrames}}}};
}

nlohmann::json PerceptionEvalResult::toJson() const {
  nlohmann::json j = all.toJson();
  nlohmann::json by = nlohmann::json::object();
  for (const auto& name : lightingOrder) by[name] = byLighting.at(name).toJson();
  j["by_lighting"] = by;
  nlohmann::json venues = nlohmann::json::object();
  for (const auto& [name, figures] : byVenue) venues[name] = figures.toJson();
  j["by_venue"] = venues;
  // Lighting independence: how much each figure drops from the brightest to the darkest preset
  // (percentage points; for false balls per frame and the error ratio, the rise x 100).
  if (byLighting.count("bright") && byLighting.count("dark")) {
    const auto &b = byLighting.at("bright"), &d = byLighting.at("dark");
    j["bright_to_dark_drop_points"] = {
        {"lines.recall", 100 * (b.lineRecall() - d.lineRecall())},
        {"lines.precision", 100 * (b.linePrecision() - d.linePrecision())},
        {"circle.detection_rate", 100 * (b.circleRate() - d.circleRate())},
        {"ball.recall_3m", 100 * (b.ballRecall3() - d.ballRecall3())},
        {"ball.recall_5m", 100 * (b.ballRecall5() - d.ballRecall5())},
        {"ball.false_per_frame", 100 * (d.falseBallsPerFrame() - b.falseBallsPerFrame())},
        {"ball.median_error_ratio", 100 * (d.medianBallErrorRatio() - b.medianBallErrorRatio())}};
  }
  j["perception_ms_median"] = median(perceptionMs);
  if (oracleFit) {
    nlohmann::json rates = nlohmann::json::object();
    const std::pair<const char*, const OracleFit::Rate*> named[] = {{"ball", &oracleFit->ball},
                                                                   {"lines_long", &oracleFit->linesLong},
                                                                   {"lines_short", &oracleFit->linesShort},
                                                                   {"circle", &oracleFit->circle},
                                                                   {"penalty_mark", &oracleFit->penaltyMark}};
    for (const auto& [name, rate] : named) rates[name] = {{"seen", rate->seen}, {"found", rate->found}};
    j["oracle_fit"] = {{"distance_bins", oracleFit->bins}, {"frames", oracleFit->frames}, {"counts", rates}};
  }
  return j;
}

PerceptionEvalResult evaluatePerception(const PerceptionEvalOptions& options) {
  // One world per venue look the trials visit (--venue random: trial t is at look
  // (seed + t) mod the count), each with its renderer; the fast percept mode renders nothing.
  struct Scene {
    std::string venue;
    std::unique_ptr<World> world;
    std::optional<CameraRenderer> renderer;
  };
  std::deque<Scene> scenes;  // references stay valid as scenes are added
  auto sceneFor = [&](int trial) -> Scene& {
    const VenueLook look = options.venue.forSeed(options.seed + static_cast<std::uint64_t>(trial));
    for (Scene& s : scenes)
      if (s.venue == look.name) return s;
    SceneSpec spec;
    spec.field = options.field;
    spec.robots = {Eigen::Vector3d::Zero()};
    spec.balls = {Eigen::Vector3d(0, 0, kBallRadius)};
    spec.venue = look;
    spec.venueSeed = options.seed;
    Scene& s = scenes.emplace_back();
    s.venue = look.name;
    s.world = std::make_unique<World>(spec, options.seed);
    if (options.percepts != "oracle") s.renderer.emplace(s.world->model());
    return s;
  };
  const World& firstWorld = *sceneFor(0).world;
  std::vector<Lighting> lightings = options.lightings;
  if (lightings.empty()) lightings.push_back(Lighting::parse("default", dataPath("config/lighting.json")));

  PerceptionEvalResult result;
  if (!options.imagesDir.empty()) io::makeDirectories(options.imagesDir);
  if (!options.failuresDir.empty()) io::makeDirectories(options.failuresDir);
  for (const auto& l : lightings) {
    result.lightingOrder.push_back(l.name);
    result.byLighting[l.name];
  }
  // The robot's vision: one camera pipeline per camera, built from the same modules.
  DebugChannels& debug = options.debug ? *options.debug : DebugChannels::none();
  CameraPipelineConfig pipelineConfig;
  pipelineConfig.debug = options.debug;
  // The exposure as the robot program would meter this view (its AutoExposureWeighting).
  const ProgramMetering metering(dataPath("config"));
  CameraPipeline pipelines[kNumCameras] = {CameraPipeline(CameraId::Top, options.field, pipelineConfig),
                                           CameraPipeline(CameraId::Bottom, options.field, pipelineConfig)};
  const FieldModel& field = firstWorld.field();
  const bool oracle = options.percepts == "oracle";
  if (!oracle && options.percepts != "vision")
    throw Error("PerceptionEvalOptions.percepts", "'" + options.percepts + "' is neither vision nor oracle");
  if (const std::string problem = modules::OracleVision::check(options.oracle); !problem.empty())
    throw Error("PerceptionEvalOptions.oracle", problem);
  if (options.fitOracle && !oracle) result.oracleFit.emplace(options.oracle.distanceBins);
  std::mt19937_64 oracleRng(options.seed ^ 0x5eed0f0cac1eULL);
  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> uni(0, 1);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * uni(rng); };

  for (int trial = 0; trial < options.trials; ++trial) {
    Scene& scene = sceneFor(trial);
    World& world = *scene.world;
    std::optional<CameraRenderer>& renderer = scene.renderer;
    // A random scene: pose anywhere on the field, head anywhere in its usual range.
    const RandomView view = randomView(field, options.maxOffsetDeg, rng);
    const Eigen::Vector3d& pose = view.pose;
    const JointArray& posture = view.posture;
    const CameraCalibration& offsets = view.offsets;
    world.setMiscalibration(0, offsets);
    world.placeRobot(0, pose, posture);
    // The ball: mostly somewhere in front of the head, at any distance up to 6 m.
    // The ball: on the field (where the game keeps it), mostly somewhere in front of the head
    // at any distance up to 6 m, never inside the robot.
    Eigen::Vector2d ball(-20, -20);
    auto onField = [&](const Eigen::Vector2d& b) {
      return std::abs(b.x()) <= field.halfLength() && std::abs(b.y()) <= field.halfWidth() &&
             (b - pose.head<2>()).norm() > 0.2;
    };
    const bool inFront = uni(rng) < options.ballProbability;
    for (int attempt = 0; attempt < 20; ++attempt) {
      Eigen::Vector2d b;
      if (inFront) {
        const double bearing = pose.z() + posture[HeadYaw] + uniform(-35, 35) * kDeg;
        const double dist = 0.12 + 5.9 * std::pow(uni(rng), 0.8);
        b = pose.head<2>() + dist * Eigen::Vector2d(std::cos(bearing), std::sin(bearing));
      } else {
        const double y = uniform(-field.halfWidth(), field.halfWidth());  // before x: the committed figures' order
        b = Eigen::Vector2d(uniform(-field.halfLength(), field.halfLength()), y);
      }
      if (onField(b)) {
        ball = b;
        break;
      }
    }
    world.placeBall(0, Eigen::Vector3d(ball.x(), ball.y(), kBallRadius));

    const SensorFrame sensors = world.sensors(0);
    const Eigen::Vector3d robotPose = world.robotPose(0);
    for (CameraId camera : {CameraId::Top, CameraId::Bottom}) {
      const CameraResolution res = world.cameraResolution(camera);
      const CameraIntrinsics in = CameraIntrinsics::fromFovY(res.width, res.height, world.cameraFovY());
      const CameraMatrix cm = computeCameraMatrix(sensors.joints.position, sensors.inertial.angle, camera, offsets, in);
      const ExposureWeights weights = metering(cm, sensors, offsets);
      const FrameTruth truth = computeTruth(world, camera);
      const OracleView sight = oracleView(world, 0, camera);
      for (const Lighting& lighting : lightings) {
        VisionResult r;
        CameraImage img;
        PerceptionFigures fig;
        if (oracle) {
          const CameraPercepts p = modules::OracleVision::perceive(sight, cm, options.oracle,
                                                                   options.field.centerCircleDiameter / 2, oracleRng);
          r.lines = p.linesPercept();
          r.ball = p.ball;
          r.penaltyMarkImage = p.penaltyMarkImage;
        } else {
          std::mt19937_64 noiseRng(options.seed * 1000003 + trial * 17 + static_cast<int>(camera));
          // Each image is its own moment in its light: the camera has settled there (and the
          // result does not depend on which trials ran before, so chunks merge exactly).
          renderer->resetCameraSensors();
          img = renderer->renderImage(world.model(), world.data(), world.cameraIndex(0, camera), res.width, res.height,
                                     lighting, camera, 0, noiseRng, weights);
          CameraPipeline& pipeline = pipelines[static_cast<int>(camera)];
          pipeline.process(img, cm);
          r = pipeline.visionResult();
          result.perceptionMs.push_back(pipeline.totalMs());
          const DenoisedImage& denoised = pipeline.get<DenoisedImage>();
          fig.imageNoise.push_back(denoised.noise);
          fig.blurredFrames += denoised.radius > 0;
        }
        scoreFrame(world, camera, truth, r, robotPose, fig, {debug, trial, lighting.name});
        result.byLighting[lighting.name].add(fig);
        result.byVenue[scene.venue].add(fig);
        result.all.add(fig);
        if (result.oracleFit) collectFit(sight, cm, r, fig, options.oracle, *result.oracleFit);
        if (oracle) continue;  // no pixels to draw
        if (!options.imagesDir.empty() && options.imagesEvery > 0 && trial % options.imagesEvery == 0) {
          const cv::Mat annotated = annotateVision(rgbFromCameraImage(img), r, cm, camera == CameraId::Bottom ? 2 : 1);
          char name[160];
          std::snprintf(name, sizeof name, "/perception_%03d_%s_%s.png", trial, cameraName(camera), lighting.name.c_str());
          writePng(options.imagesDir + name, annotated);
        }
        if (!options.failuresDir.empty()) {
          std::string what;
          if (fig.trueLinesFound < fig.trueLines) what += "_linemiss";
          if (fig.detectedLinesMatched < fig.detectedLines) what += "_linefalse";
          if (fig.circleFound < fig.circleFrames) what += "_circlemiss";
          if (fig.circleFalse) what += "_circlefalse";
          if (fig.found5 < fig.balls5) what += "_ballmiss";
          if (fig.falseBalls) what += "_ballfalse";
          if (!what.empty()) {
            const cv::Mat annotated = annotateVision(rgbFromCameraImage(img), r, cm, camera == CameraId::Bottom ? 2 : 1);
            char name[200];
            std::snprintf(name, sizeof name, "/fail_%03d_%s_%s%s", trial, cameraName(camera), lighting.name.c_str(),
                          what.c_str());
            writePng(options.failuresDir + name + ".png", annotated);
            writePng(options.failuresDir + name + "_raw.png", img);
            // How to render this scene again.
            const auto deg = offsets.toArray();
            std::string how;
            auto line = [&how](const char* format, auto... values) {
              char buf[512];
              std::snprintf(buf, sizeof buf, format, values...);
              how += buf;
            };
            line("render --camera %s --pose %.4f,%.4f,%.3f --head %.3f,%.3f --ball %.3f,%.3f --lighting %s "
                 "--venue %s --seed %llu --miscalibration %.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n",
                 cameraName(camera), pose.x(), pose.y(), pose.z() * 180 / M_PI, posture[HeadYaw] * 180 / M_PI,
                 posture[HeadPitch] * 180 / M_PI, ball.x(), ball.y(), lighting.name.c_str(), scene.venue.c_str(),
                 static_cast<unsigned long long>(options.seed), deg[0] / kDeg,
                 deg[1] / kDeg, deg[2] / kDeg, deg[3] / kDeg, deg[4] / kDeg, deg[5] / kDeg);
            for (const auto& tl : truth.lines)
              line("line %s vis %.2f img %.0f %.0f %.0f %.0f\n", tl.name.c_str(), tl.visibleLength, tl.imageFrom.x(),
                   tl.imageFrom.y(), tl.imageTo.x(), tl.imageTo.y());
            for (const auto& b : truth.balls5)
              line("ball_px %.1f %.1f r %.1f dist %.2f\n", b.image.x(), b.image.y(), b.radiusPx, b.distance);
            io::writeFile(options.failuresDir + name + ".txt", how);
          }
        }
      }
    }
    if (options.progress) options.progress(trial + 1, options.trials);
  }
  return result;
}

}  // namespace nao::sim
