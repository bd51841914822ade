#include "scenarios/Calibrate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include <opencv2/imgproc.hpp>

#include "controllers/StandController.h"
#include "perception/CameraModel.h"
#include "perception/Geometry.h"
#include "perception/calibration/SampleExtraction.h"
#include "robot/Error.h"
#include "robot/OutputFiles.h"
#include "sim/CameraRenderer.h"
#include "sim/GroundTruth.h"
#include "sim/ImageIO.h"
#include "sim/SimBackend.h"
#include "sim/World.h"

namespace nao::sim {
namespace {

namespace cal = nao::calibration;
constexpr double kDeg = M_PI / 180;

// What one view captured, with the truth kept for scoring.
struct Capture {
  CameraImage image;
  SensorFrame sensors;
  Eigen::Vector3d truePose = Eigen::Vector3d::Zero();
  CameraIntrinsics intrinsics;
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> truth;  // field point, its true pixel
  cal::ExtractionResult extraction;
  int sample = -1;  // index into the samples, -1 if rejected
};

// Visible field-line points of a view every 5 cm (ray-cast occlusion) and their true pixels.
std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> visibleLinePoints(const World& world, CameraId camera) {
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> out;
  const VisibleFeatures vis = visibleFeatures(world, 0, camera, 8.0);
  for (const VisibleLine& l : vis.lines) {
    const double len = (l.to - l.from).norm();
    const int n = std::max(1, static_cast<int>(len / 0.05));
    for (int i = 0; i <= n; ++i) {
      const Eigen::Vector2d p = l.from + (l.to - l.from) * (static_cast<double>(i) / n);
      if (const auto px = truePixel(world, 0, camera, Eigen::Vector3d(p.x(), p.y(), 0))) out.emplace_back(p, *px);
    }
  }
  return out;
}

// Projected field lines (red) and the field border (orange) over an RGB image, as in the
// paper's Fig. 2. The robot pose is the true one: the picture shows the projection only.
void drawProjectedField(cv::Mat& rgb, const CameraMatrix& cm, const Eigen::Vector3d& robotPose, const FieldModel& field,
                        double scale) {
  auto polyline = [&](const std::vector<Eigen::Vector2d>& pts, const cv::Scalar& colour) {
    std::optional<Eigen::Vector2d> prev;
    for (const auto& p : pts) {
      const Eigen::Vector2d rel = fieldToRobot(p, robotPose);
      const Eigen::Vector3d inCam = cm.robotToCamera(Eigen::Vector3d(rel.x(), rel.y(), 0));
      std::optional<Eigen::Vector2d> px;
      if (inCam.x() > 0.05) px = cm.project(Eigen::Vector3d(rel.x(), rel.y(), 0));
      if (px && prev)
        cv::line(rgb, cv::Point2d(prev->x() * scale, prev->y() * scale), cv::Point2d(px->x() * scale, px->y() * scale),
                 colour, 1, cv::LINE_AA);
      prev = px;
    }
  };
  auto segment = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const cv::Scalar& colour) {
    const int n = std::max(2, static_cast<int>((b - a).norm() / 0.02));
    std::vector<Eigen::Vector2d> pts;
    for (int i = 0; i <= n; ++i) pts.push_back(a + (b - a) * (static_cast<double>(i) / n));
    polyline(pts, colour);
  };
  const cv::Scalar red(255, 0, 0), orange(255, 150, 0);  // RGB order
  for (const auto& l : field.lines) segment(l.from, l.to, red);
  std::vector<Eigen::Vector2d> circle;
  for (int i = 0; i <= 180; ++i) {
    const double a = 2 * M_PI * i / 180;
    circle.push_back(field.centerCircleCenter + field.centerCircleRadius * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  polyline(circle, red);
  const double bx = field.halfLength() + field.dims.borderStripWidth, by = field.halfWidth() + field.dims.borderStripWidth;
  const Eigen::Vector2d c[4] = {{-bx, -by}, {bx, -by}, {bx, by}, {-bx, by}};
  for (int i = 0; i < 4; ++i) segment(c[i], c[(i + 1) % 4], orange);
}

// A view with what the finder and refiner made of it: LSD line segments (blue), the goal box
// lines' refined edges (yellow), and the verdict.
cv::Mat annotateView(const Capture& c) {
  cv::Mat rgb = rgbFromCameraImage(c.image);
  const double s = c.image.width < 640 ? 2 : 1;
  cv::resize(rgb, rgb, cv::Size(), s, s, cv::INTER_NEAREST);
  auto pt = [&](const Eigen::Vector2d& p) { return cv::Point2d(p.x() * s, p.y() * s); };
  for (const auto& seg : c.extraction.segments) cv::line(rgb, pt(seg.from), pt(seg.to), cv::Scalar(60, 120, 255), 1, cv::LINE_AA);
  if (c.extraction.sample)
    for (const auto& l : c.extraction.sample->lines)
      for (const ImageLine* e : {&l.edgeA, &l.edgeB}) cv::line(rgb, pt(e->from), pt(e->to), cv::Scalar(255, 230, 0), 1, cv::LINE_AA);
  const std::string text = c.extraction.sample ? "sample" : c.extraction.reason;
  cv::putText(rgb, text, cv::Point(6, 18), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  return rgb;
}

// Top image above the bottom one (each at its own resolution, centred), field projected with
// `calib`.
cv::Mat figure(const Capture& top, const Capture& bottom, const CameraCalibration& calib, const FieldModel& field) {
  cv::Mat parts[2];
  const Capture* caps[2] = {&top, &bottom};
  int width = 0;
  for (int k = 0; k < 2; ++k) {
    const Capture& c = *caps[k];
    cv::Mat rgb = rgbFromCameraImage(c.image);
    const CameraMatrix cm = computeCameraMatrix(c.sensors.joints.position, c.sensors.inertial.angle, c.image.camera,
                                                calib, c.intrinsics);
    drawProjectedField(rgb, cm, c.truePose, field, 1.0);
    parts[k] = rgb;
    width = std::max(width, rgb.cols);
  }
  cv::Mat out(parts[0].rows + parts[1].rows, width, CV_8UC3, cv::Scalar(0, 0, 0));
  parts[0].copyTo(out(cv::Rect((width - parts[0].cols) / 2, 0, parts[0].cols, parts[0].rows)));
  parts[1].copyTo(out(cv::Rect((width - parts[1].cols) / 2, parts[0].rows, parts[1].cols, parts[1].rows)));
  return out;
}

double reprojectionRms(const std::vector<Capture>& caps, const CameraCalibration& calib, int* points) {
  double sum2 = 0;
  int n = 0;
  for (const Capture& c : caps) {
    if (c.sample < 0) continue;
    const CameraMatrix cm = computeCameraMatrix(c.sensors.joints.position, c.sensors.inertial.angle, c.image.camera,
                                                calib, c.intrinsics);
    for (const auto& [p, truePx] : c.truth) {
      const auto px = cm.fieldToImage(p, c.truePose);
      if (!px) continue;
      sum2 += (*px - truePx).squaredNorm();
      ++n;
    }
  }
  if (points) *points = n;
  return n ? std::sqrt(sum2 / n) : 0;
}

}  // namespace

double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(q * values.size()));
  return values[std::clamp<std::size_t>(rank, 1, values.size()) - 1];
}

CalibrationRunResult runCalibration(const CalibrationRunOptions& o) {
  const auto wall0 = std::chrono::steady_clock::now();
  CalibrationRunResult result;
  result.truth = o.miscalibration;
  if (!o.imagesDir.empty()) {
    io::makeDirectories(o.imagesDir);
  }

  // The world: the robot at the challenge's initial position.
  const Eigen::Vector3d start = cal::initialPosition(o.field, o.side);
  SceneSpec spec;
  spec.field = o.field;
  spec.robotModel = o.robotModel;
  spec.robots = {start};
  World world(spec, o.seed);
  world.setMiscalibration(0, o.miscalibration);
  const JointArray stand = StandController::standPosture();
  world.placeRobot(0, start, stand);
  result.headId = SimBackend(world, 0, false).robotInfo().headId;
  CameraRenderer renderer(world.model());
  std::mt19937_64 noiseRng(o.seed ^ 0x5deece66dULL);

  // The robot program's plan, from where it believes it stands.
  const cal::GoalBoxSide side = cal::ownGoalBoxSide(o.field, o.side);
  const Eigen::Vector3d calPose = cal::calibrationPosition(side, o.views);
  const std::vector<cal::CalibrationView> views = cal::planViews(side, calPose.head<2>(), stand, o.views);
  cal::ExtractionOptions extraction;
  extraction.goalBoxDepth = o.field.goalBoxAreaLength;
  extraction.lineWidth = o.field.lineWidth;
  extraction.source = o.lineSource;

  std::vector<Capture> captures;
  std::vector<cal::CalibrationSample> samples;
  for (const cal::CalibrationView& v : views) {
    // TO BE REPLACED BY WALKING: teleport to the view's pose (position and heading), off by the
    // placement error; the walk will turn the robot there.
    const double c = std::cos(calPose.z()), s = std::sin(calPose.z());
    const Eigen::Vector3d truePose(v.robotPose.x() + c * o.placementError.x() - s * o.placementError.y(),
                                   v.robotPose.y() + s * o.placementError.x() + c * o.placementError.y(),
                                   v.robotPose.z() + o.placementError.z());
    JointArray posture = stand;
    posture[HeadYaw] = v.headYaw;
    posture[HeadPitch] = v.headPitch;
    world.placeRobot(0, truePose, posture);
    // Hold still: settle, then wait until the head joints stop moving.
    JointArray last = world.sensors(0).joints.position;
    const double until = world.time() + o.settleSeconds;
    for (int cycle = 0; cycle < 400; ++cycle) {
      world.stepCycle();
      const JointArray now = world.sensors(0).joints.position;
      const bool still = std::abs(now[HeadYaw] - last[HeadYaw]) < 1e-6 && std::abs(now[HeadPitch] - last[HeadPitch]) < 1e-6;
      last = now;
      if (world.time() >= until && still) break;
    }
    Capture cap;
    cap.sensors = world.sensors(0);
    cap.truePose = world.robotPose(0);
    const CameraResolution res = world.cameraResolution(v.camera);
    cap.intrinsics = CameraIntrinsics::fromFovY(res.width, res.height, world.cameraFovY());
    cap.image = renderer.renderImage(world.model(), world.data(), world.cameraIndex(0, v.camera), res.width, res.height,
                                     o.lighting, v.camera, world.time(), noiseRng);
    cap.truth = visibleLinePoints(world, v.camera);
    // The robot program's side: image + joint angles + IMU at capture time.
    const auto extract0 = std::chrono::steady_clock::now();
    cap.extraction = cal::extractSample(cap.image, cap.sensors.joints.position, cap.sensors.inertial.angle, cap.intrinsics,
                                        CameraCalibration{}, extraction);
    const double extractMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - extract0).count();
    ViewRecord rec;
    rec.camera = v.camera;
    rec.headYawDeg = cap.sensors.joints.position[HeadYaw] / kDeg;
    rec.headPitchDeg = cap.sensors.joints.position[HeadPitch] / kDeg;
    rec.accepted = cap.extraction.sample.has_value();
    rec.reason = cap.extraction.reason;
    rec.extractMs = extractMs;
    rec.source = cap.extraction.source;
    if (rec.accepted) {
      cap.sample = static_cast<int>(samples.size());
      samples.push_back(*cap.extraction.sample);
    }
    result.views.push_back(rec);
    captures.push_back(std::move(cap));
  }
  result.samples = static_cast<int>(samples.size());
  result.sampleData = samples;

  cal::CalibratorOptions copts = o.calibrator;
  copts.cost.goalBoxDepth = o.field.goalBoxAreaLength;
  try {
    result.solution = cal::solveCalibration(samples, copts);
  } catch (const Error& e) {
    // Too few samples: no estimate; the views say why.
    result.solution = {};
    result.solution.reason = e.what();
    result.solution.solver.message = e.what();
  }
  result.estimate = result.solution.offsets;
  // Samples dropped as outliers do not count as accepted views.
  for (const auto& [index, why] : result.solution.dropped)
    for (std::size_t k = 0; k < captures.size(); ++k)
      if (captures[k].sample == index) {
        result.views[k].accepted = false;
        result.views[k].reason = "dropped after the solve: " + why;
      }
  for (std::size_t i = 0; i < result.solution.used.size(); ++i)
    for (std::size_t k = 0; k < captures.size(); ++k)
      if (captures[k].sample == result.solution.used[i]) result.views[k].residuals = result.solution.residuals[i];
  if (o.compareSolvers && !result.solution.used.empty()) {
    std::vector<cal::CalibrationSample> used;
    for (int i : result.solution.used) used.push_back(samples[i]);
    const cal::CalibrationCost cost(used, copts.cost);
    const cal::SolverKind other =
        copts.solver == cal::SolverKind::GaussNewton ? cal::SolverKind::Ceres : cal::SolverKind::GaussNewton;
    result.otherSolver = cal::solveWith(other, cost, copts);
  }

  result.reprojectionPx = reprojectionRms(captures, result.estimate, &result.reprojectionPoints);
  result.reprojectionBeforePx = reprojectionRms(captures, CameraCalibration{}, nullptr);

  if (!o.imagesDir.empty()) {
    for (std::size_t k = 0; k < captures.size(); ++k) {
      char name[96];
      std::snprintf(name, sizeof name, "/view_%02zu_%s_yaw%+04d.png", k, cameraName(captures[k].image.camera),
                    static_cast<int>(std::lround(result.views[k].headYawDeg)));
      writePng(o.imagesDir + name, annotateView(captures[k]));
      result.imagesWritten.push_back(o.imagesDir + name);
      std::snprintf(name, sizeof name, "/view_%02zu_%s_yaw%+04d_raw.png", k, cameraName(captures[k].image.camera),
                    static_cast<int>(std::lround(result.views[k].headYawDeg)));
      writePng(o.imagesDir + name, captures[k].image);
      result.imagesWritten.push_back(o.imagesDir + name);
    }
    // Fig. 2: the views nearest to a straight head, before and after.
    auto straightest = [&](CameraId cam) -> const Capture* {
      const Capture* best = nullptr;
      for (const Capture& c : captures)
        if (c.image.camera == cam &&
            (!best || std::abs(c.sensors.joints.position[HeadYaw]) < std::abs(best->sensors.joints.position[HeadYaw])))
          best = &c;
      return best;
    };
    const Capture* top = straightest(CameraId::Top);
    const Capture* bottom = straightest(CameraId::Bottom);
    if (top && bottom) {
      writePng(o.imagesDir + "/calibration_before.png", figure(*top, *bottom, CameraCalibration{}, world.field()));
      writePng(o.imagesDir + "/calibration_after.png", figure(*top, *bottom, result.estimate, world.field()));
      result.imagesWritten.push_back(o.imagesDir + "/calibration_before.png");
      result.imagesWritten.push_back(o.imagesDir + "/calibration_after.png");
    }
  }
  result.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return result;
}

CalibrationEvalResult evalCalibration(const CalibrationEvalOptions& o) {
  if (o.trials < 1) throw Error("--trials", "must be at least 1");
  if (o.lightings.empty()) throw Error("calibration eval", "no lighting presets");
  CalibrationEvalResult result;
  std::array<std::vector<double>, 6> errors;
  std::vector<double> reprojection, solveSeconds;
  for (int t = 0; t < o.trials; ++t) {
    std::mt19937_64 rng(o.seed * 1000003ULL + static_cast<std::uint64_t>(t));
    std::uniform_real_distribution<double> uni(-1, 1);
    CalibrationRunOptions run;
    run.field = o.field;
    run.robotModel = o.robotModel;
    std::array<double, 6> offsets{};
    for (double& v : offsets) v = uni(rng) * o.maxOffsetDeg * kDeg;
    run.miscalibration = CameraCalibration::fromArray(offsets);
    // Placement error: uniform in a disc of maxPlacementError, heading uniform in +-max.
    const double r = o.maxPlacementError * std::sqrt(0.5 * (uni(rng) + 1)), a = M_PI * uni(rng);
    run.placementError = Eigen::Vector3d(r * std::cos(a), r * std::sin(a), uni(rng) * o.maxHeadingErrorDeg * kDeg);
    const std::size_t li = static_cast<std::size_t>(rng() % o.lightings.size());
    run.lighting = o.lightings[li];
    run.calibrator.solver = o.solver;
    run.calibrator.cost = o.cost;
    run.views = o.views;
    run.lineSource = o.lineSource;
    run.compareSolvers = true;
    run.seed = o.seed * 7919 + static_cast<std::uint64_t>(t);

    CalibrationTrial trial;
    trial.lighting = run.lighting.name;
    trial.placementError = run.placementError;
    trial.run = runCalibration(run);
    const CalibrationRunResult& res = trial.run;
    ++result.trials;
    if (res.solution.solver.converged && res.otherSolver && res.otherSolver->converged) ++result.converged;
    if (res.solution.accepted) ++result.accepted;
    const auto est = res.estimate.toArray(), truth = res.truth.toArray();
    for (int k = 0; k < 6; ++k) {
      errors[k].push_back(std::abs(est[k] - truth[k]) / kDeg);
      if (res.otherSolver)
        result.solverAgreementMaxDeg = std::max(result.solverAgreementMaxDeg, std::abs(res.otherSolver->x[k] - est[k]) / kDeg);
    }
    reprojection.push_back(res.reprojectionPx);
    solveSeconds.push_back(res.solution.solveSeconds);
    result.solveSecondsMax = std::max(result.solveSecondsMax, res.solution.solveSeconds);
    if (res.otherSolver) result.otherSolveSecondsMax = std::max(result.otherSolveSecondsMax, res.otherSolver->seconds);
    result.trialResults.push_back(std::move(trial));
    if (o.progress) o.progress(t + 1, o.trials);
  }
  for (int k = 0; k < 6; ++k) {
    result.medianAbsErrorDeg[k] = quantile(errors[k], 0.5);
    result.p95AbsErrorDeg[k] = quantile(errors[k], 0.95);
    result.maxAbsErrorDeg[k] = quantile(errors[k], 1.0);
  }
  result.reprojectionMedianPx = quantile(reprojection, 0.5);
  result.reprojectionP95Px = quantile(reprojection, 0.95);
  result.reprojectionMaxPx = quantile(reprojection, 1.0);
  result.solveSecondsMedian = quantile(solveSeconds, 0.5);
  return result;
}

}  // namespace nao::sim
