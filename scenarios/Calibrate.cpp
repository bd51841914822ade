#include "scenarios/Calibrate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include <opencv2/imgproc.hpp>

#include "controllers/CalibrationLogging.h"
#include "controllers/RobotProgram.h"
#include "controllers/StandController.h"
#include "perception/CameraModel.h"
#include "perception/Geometry.h"
#include "perception/calibration/SampleExtraction.h"
#include "representations/behavior/SpeechRequest.h"
#include "representations/perception/CalibrationStatus.h"
#include "robot/Error.h"
#include "robot/Parameters.h"
#include "robot/OutputFiles.h"
#include "sim/CameraRenderer.h"
#include "sim/GroundTruth.h"
#include "sim/ImageIO.h"
#include "sim/SimBackend.h"
#include "sim/World.h"
#include "scenarios/ChallengeSession.h"

namespace nao::sim {
namespace {

namespace cal = nao::calibration;
constexpr double kDeg = M_PI / 180;

// What one view the robot's calibrator judged looked like, with the truth kept for scoring.
struct Capture {
  CameraImage image;
  SensorFrame sensors;
  Eigen::Vector3d truePose = Eigen::Vector3d::Zero();
  CameraIntrinsics intrinsics;
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> truth;  // field point, its true pixel
  std::string verdict;  // "sample" or why not
  int sample = -1;      // index into the robot's samples, -1 if rejected
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

// A view with the robot's verdict on it.
cv::Mat annotateView(const Capture& c) {
  cv::Mat rgb = rgbFromCameraImage(c.image);
  const double s = c.image.width < 640 ? 2 : 1;
  cv::resize(rgb, rgb, cv::Size(), s, s, cv::INTER_NEAREST);
  cv::putText(rgb, c.verdict, cv::Point(6, 18), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
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

CameraImage shieldFrame(const World& world, CameraId cam, double time) {
  const CameraResolution res = world.cameraResolution(cam);
  CameraImage img;
  img.camera = cam;
  img.width = res.width;
  img.height = res.height;
  img.timestamp = time;
  img.yuyv.assign(static_cast<std::size_t>(res.width) * res.height * 2, 16);
  for (std::size_t i = 1; i < img.yuyv.size(); i += 2) img.yuyv[i] = 128;
  return img;
}

ChallengeSetup challengeSetup(const CalibrationRunOptions& o) {
  ChallengeSetup setup;
  setup.field = o.field;
  setup.robotModel = o.robotModel;
  setup.miscalibration = o.miscalibration;
  setup.lighting = o.lighting;
  setup.side = o.side;
  setup.seed = o.seed;
  setup.randomize = o.randomize;
  setup.floorFriction = o.floorFriction;
  setup.venue = o.venue;
  setup.calibrator = o.calibrator;
  setup.debug = o.debug;
  return setup;
}

std::array<Eigen::Vector2d, 2> phaseOneBalls(const FieldDimensions& field, std::uint64_t seed) {
  // Roughly in the centre of each half, clear of lines (the rules' phase 1).
  std::mt19937_64 rng(seed * 0x9e3779b97f4a7c15ULL + 3);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  std::array<Eigen::Vector2d, 2> balls;
  for (int i = 0; i < 2; ++i) {
    const double y = jitter(rng);  // before x: the order the committed figures were made with
    balls[i] = Eigen::Vector2d((i ? 1 : -1) * field.length / 4 + jitter(rng), y);
  }
  return balls;
}

CalibrationRunResult runCalibration(const CalibrationRunOptions& o) {
  ChallengeSession session(challengeSetup(o));
  CalibrationRunResult result;
  runCalibrationPhase(session, o, result);
  return result;
}

void runCalibrationPhase(ChallengeSession& session, const CalibrationRunOptions& o, CalibrationRunResult& result) {
  const auto wall0 = std::chrono::steady_clock::now();
  result.truth = o.miscalibration;
  result.headId = session.headId();
  if (!o.imagesDir.empty()) io::makeDirectories(o.imagesDir);
  World& world = session.world();
  RobotProgram& program = session.program();

  // Every view the calibrator judged: the image it judged, with the truth at its exposure. The
  // observer stays with the session (it outlives this phase), so its state is shared.
  struct Views {
    std::vector<Capture> captures;
    int lastView = -1;
  };
  auto views = std::make_shared<Views>();
  session.addCognitionObserver([views, &world, &result](const CameraImage& image, const Blackboard& cognition) {
    if (!cognition.has<CalibrationStatus>()) return;
    const CalibrationStatus& status = cognition.read<CalibrationStatus>();
    if (status.last.viewId == views->lastView || status.last.imageTime != image.timestamp) return;
    views->lastView = status.last.viewId;
    Capture cap;
    cap.image = image;
    cap.sensors = world.sensors(0);
    cap.truePose = world.robotPose(0);
    cap.intrinsics = CameraIntrinsics::fromFovY(image.width, image.height, world.cameraFovY());
    cap.truth = visibleLinePoints(world, image.camera);
    cap.verdict = status.last.accepted ? "sample" : status.last.reason;
    if (status.last.accepted) cap.sample = result.samples++;
    ViewRecord rec;
    rec.camera = image.camera;
    rec.headYawDeg = cap.sensors.joints.position[HeadYaw] / kDeg;
    rec.headPitchDeg = cap.sensors.joints.position[HeadPitch] / kDeg;
    rec.accepted = status.last.accepted;
    rec.reason = status.last.reason;
    rec.extractMs = status.last.extractMs;
    rec.source = status.last.source;
    rec.truePose = cap.truePose;
    result.views.push_back(rec);
    if (status.last.accepted)
      result.accepted.push_back({image, cap.sensors.joints.position, cap.sensors.inertial.angle});
    views->captures.push_back(std::move(cap));
  });
  std::vector<Capture>& captures = views->captures;
  std::shared_ptr<CalibrationRecorder> recorder;
  if (!o.recordPath.empty()) {
    recorder = std::make_shared<CalibrationRecorder>(session.headId(), "sim");
    session.addCognitionObserver(
        [recorder](const CameraImage& image, const Blackboard& cognition) { recorder->observe(image, cognition); });
  }

  // Two balls near the halves' centres, the shield, then the start signal: chest + head front
  // held 1.2 s; the rules' clock starts when the hold reaches 1 s (the robot's own rule fires then).
  const std::size_t firstEvent = session.events().size();
  session.placeBalls(o.balls ? *o.balls : phaseOneBalls(o.field, o.seed));
  if (o.shieldSeconds > 0) {
    session.setShield(true);
    session.runFor(o.shieldSeconds);
    session.setShield(false);
  }
  const double phaseStart = session.startMode(false);
  if (o.progress) session.progress = [&](double t) { o.progress(t - phaseStart); };
  const double pathBefore = session.pathLength();
  while (const std::optional<ChallengeReport> report = session.untilReport(phaseStart + o.timeLimit)) {
    if (report->text == "Calibration finished") {
      result.finished = true;
      break;
    }
  }
  session.progress = nullptr;
  result.phaseSeconds = session.time() - phaseStart;
  result.terminated = session.terminated();
  if (result.terminated.empty() && !result.finished) {
    result.terminated = "phase_time";
    session.note("termination", "phase_time: no \"Calibration finished\" within the phase's time");
  }
  if (recorder) recorder->write(o.recordPath);
  result.pathLength = session.pathLength() - pathBefore;
  result.maxStep = session.maxStep();
  result.fell = session.falls() > 0;
  for (std::size_t k = firstEvent; k < session.events().size(); ++k) {
    ChallengeEvent e = session.events()[k];
    e.t -= phaseStart;
    result.events.push_back(e);
  }

  const CalibrationStatus& status = program.cognitionBoard().read<CalibrationStatus>();
  result.solution = status.solution;
  result.otherSolver = status.otherSolver;
  result.applied = status.appliedId > 0;
  result.estimate = result.applied ? status.applied : status.solution.offsets;
  result.verifyAngleDeg = status.verifyAngleDeg;
  // Samples dropped as outliers do not count as accepted views.
  for (const auto& [index, why] : result.solution.dropped)
    for (std::size_t k = 0; k < captures.size(); ++k)
      if (captures[k].sample == index) {
        result.views[k].accepted = false;
        result.views[k].reason = "dropped after the solve: " + why;
      }
  for (std::size_t i = 0; i < result.solution.used.size() && i < result.solution.residuals.size(); ++i)
    for (std::size_t k = 0; k < captures.size(); ++k)
      if (captures[k].sample == result.solution.used[i]) result.views[k].residuals = result.solution.residuals[i];

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
    // Fig. 2: the accepted views nearest to a straight head, before and after.
    auto straightest = [&](CameraId cam) -> const Capture* {
      const Capture* best = nullptr;
      for (const Capture& c : captures)
        if (c.image.camera == cam && c.sample >= 0 &&
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
}

CalibrationTrial runCalibrationTrial(const CalibrationEvalOptions& o, std::uint64_t seed) {
  if (o.lightings.empty()) throw Error("calibration eval", "no lighting presets");
  modules::Calibrator::Params calibrator =
      loadParams<modules::Calibrator::Params>("Calibrator", RobotProgramConfig::defaultConfigDir());
  calibrator.solver = cal::solverName(o.solver);
  calibrator.compareSolvers = o.compareSolvers;
  std::mt19937_64 rng(seed * 1000003ULL);
  std::uniform_real_distribution<double> uni(-1, 1);
  CalibrationRunOptions run;
  run.field = o.field;
  run.robotModel = o.robotModel;
  std::array<double, 6> offsets{};
  for (double& v : offsets) v = uni(rng) * o.maxOffsetDeg * kDeg;
  run.miscalibration = CameraCalibration::fromArray(offsets);
  const std::size_t li = static_cast<std::size_t>(rng() % o.lightings.size());
  run.lighting = o.lightings[li];
  run.side = rng() % 2 ? 1 : -1;
  run.calibrator = calibrator;
  run.seed = seed * 7919;
  run.timeLimit = o.timeLimit;
  run.venue = o.venue.forSeed(seed);
  run.randomize = o.randomize;
  run.debug = o.debug;
  if (!o.imagesDir.empty()) run.imagesDir = o.imagesDir + "/seed_" + std::to_string(seed);

  CalibrationTrial trial;
  trial.lighting = run.lighting.name;
  trial.venue = run.venue.name;
  trial.side = run.side;
  trial.run = runCalibration(run);
  return trial;
}

CalibrationEvalResult evalCalibration(const CalibrationEvalOptions& o) {
  if (o.trials < 1) throw Error("--trials", "must be at least 1");
  if (o.lightings.empty()) throw Error("calibration eval", "no lighting presets");
  CalibrationEvalResult result;
  std::array<std::vector<double>, 6> errors;
  std::vector<double> reprojection, solveSeconds, phaseSeconds;
  for (int t = 0; t < o.trials; ++t) {
    CalibrationTrial trial = runCalibrationTrial(o, o.seed + static_cast<std::uint64_t>(t));
    const CalibrationRunResult& res = trial.run;
    ++result.trials;
    result.finished += res.finished;
    if (res.solution.solver.converged && (!o.compareSolvers || (res.otherSolver && res.otherSolver->converged)))
      ++result.converged;
    if (res.solution.accepted && res.applied) ++result.accepted;
    const auto est = res.estimate.toArray(), truth = res.truth.toArray();
    for (int k = 0; k < 6; ++k) {
      errors[k].push_back(std::abs(est[k] - truth[k]) / kDeg);
      if (res.otherSolver)
        result.solverAgreementMaxDeg =
            std::max(result.solverAgreementMaxDeg, std::abs(res.otherSolver->x[k] - res.solution.offsets.toArray()[k]) / kDeg);
    }
    reprojection.push_back(res.reprojectionPx);
    solveSeconds.push_back(res.solution.solveSeconds);
    phaseSeconds.push_back(res.phaseSeconds);
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
  result.phaseSecondsMedian = quantile(phaseSeconds, 0.5);
  result.phaseSecondsMax = quantile(phaseSeconds, 1.0);
  return result;
}

}  // namespace nao::sim
