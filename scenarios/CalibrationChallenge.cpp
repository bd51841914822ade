#include "scenarios/CalibrationChallenge.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <map>
#include <random>

#include "perception/calibration/CalibrationViews.h"
#include "perception/vision/Annotate.h"
#include "sim/ImageIO.h"
#include "robot/Error.h"
#include "sim/World.h"

namespace nao::sim {

namespace {

constexpr double kDeg = M_PI / 180;
constexpr double kLineClearance = 0.15;  // m from a ball's centre to a line's centre or a mark
constexpr double kTargetClearance = 0.6; // m from the start and the three spots

const char* const kTasks[5] = {"ball_own", "walk_own_goal", "walk_center", "ball_opponent", "walk_opponent_goal"};

double segmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

// The distance from p to the nearest painted line, the circle or a mark.
double lineDistance(const FieldModel& field, const Eigen::Vector2d& p) {
  double d = std::abs((p - field.centerCircleCenter).norm() - field.centerCircleRadius);
  for (const FieldLine& l : field.lines) d = std::min(d, segmentDistance(p, l.from, l.to));
  for (const Eigen::Vector2d& c : field.penaltyCrosses) d = std::min(d, (p - c).norm());
  return std::min(d, (p - field.centerMark).norm());
}

std::array<Eigen::Vector2d, 3> spots(const FieldDimensions& f) {
  return {Eigen::Vector2d(-f.length / 2, 0), Eigen::Vector2d(0, 0), Eigen::Vector2d(f.length / 2, 0)};
}

nlohmann::json vec(const Eigen::Vector2d& v) { return {v.x(), v.y()}; }
nlohmann::json optionalNumber(const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(); }
}  // namespace

ChallengeDraw challengeDraw(std::uint64_t seed, double maxOffsetDeg) {
  std::mt19937_64 rng(seed * 0xd1b54a32d192ed03ULL + 7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::array<double, 6> offsets{};
  for (double& v : offsets) v = u(rng) * maxOffsetDeg * kDeg;
  ChallengeDraw d;
  d.offsets = CameraCalibration::fromArray(offsets);
  d.side = rng() % 2 ? 1 : -1;
  return d;
}

std::optional<Eigen::Vector2d> parseBallSentence(const std::string& text) {
  static const std::string prefix = "The ball is at: ";
  if (text.compare(0, prefix.size(), prefix) != 0) return std::nullopt;
  std::size_t at = prefix.size();
  auto integer = [&](long& value) {
    const std::size_t start = at;
    if (at < text.size() && text[at] == '-') ++at;
    const std::size_t digits = at;
    while (at < text.size() && text[at] >= '0' && text[at] <= '9') ++at;
    if (at == digits || at - digits > 9) return false;
    value = std::stol(text.substr(start, at - start));
    return true;
  };
  long x = 0, y = 0;
  if (!integer(x) || at >= text.size() || text[at++] != ' ' || !integer(y) || at != text.size()) return std::nullopt;
  return Eigen::Vector2d(static_cast<double>(x) / 1000, static_cast<double>(y) / 1000);
}

double roundTo(double value, double step) { return std::round(value / step) * step; }

void checkBalls(const FieldDimensions& field, const std::array<Eigen::Vector2d, 2>& balls, const std::string& source) {
  const FieldModel model = FieldModel::from(field);
  for (int i = 0; i < 2; ++i) {
    const Eigen::Vector2d& b = balls[i];
    const std::string name = i ? "the opponent half's ball" : "the own half's ball";
    if (!b.allFinite() || std::abs(b.x()) > field.length / 2 || std::abs(b.y()) > field.width / 2)
      throw Error(source, name + " lies outside the field");
    if ((i == 0) != (b.x() < 0)) throw Error(source, name + " lies in the other half");
    if (lineDistance(model, b) < field.lineWidth / 2 + 0.05) throw Error(source, name + " lies on a line");
  }
}

std::array<Eigen::Vector2d, 2> phaseTwoBalls(const FieldDimensions& field, std::uint64_t seed, int side) {
  const FieldModel model = FieldModel::from(field);
  std::mt19937_64 rng(seed * 0xbf58476d1ce4e5b9ULL + 11);
  std::uniform_real_distribution<double> ux(0.3, field.length / 2 - 0.3), uy(-(field.width / 2 - 0.3), field.width / 2 - 0.3);
  const Eigen::Vector2d start = calibration::initialPosition(field, side).head<2>();
  std::array<Eigen::Vector2d, 2> balls;
  for (int i = 0; i < 2; ++i) {
    for (int attempt = 0;; ++attempt) {
      if (attempt > 100000) throw Error("calibration challenge", "no ball positions fit this field");
      const double y = uy(rng);  // before x: the order the committed figures were made with
      const Eigen::Vector2d b((i ? 1 : -1) * ux(rng), y);
      if (lineDistance(model, b) < kLineClearance) continue;
      if ((b - start).norm() < kTargetClearance) continue;
      bool nearSpot = false;
      for (const Eigen::Vector2d& s : spots(field)) nearSpot = nearSpot || (b - s).norm() < kTargetClearance;
      if (nearSpot || (i == 1 && (b - balls[0]).norm() < kTargetClearance)) continue;
      balls[i] = b;
      break;
    }
  }
  return balls;
}

ChallengeResult runChallenge(const ChallengeOptions& o) {
  ChallengeResult result;
  ChallengeSession session(challengeSetup(o.run));
  result.headId = session.headId();
  result.robot = session.robotJson();
  result.phaseOneBalls = o.run.balls ? *o.run.balls : phaseOneBalls(o.run.field, o.run.seed);
  result.phaseTwoBalls = o.phaseTwoBalls ? *o.phaseTwoBalls : phaseTwoBalls(o.run.field, o.run.seed, o.run.side);
  auto finish = [&] {
    result.terminated = session.terminated();
    result.falls = session.falls();
    result.events = session.events();
    result.pathLength = session.pathLength();
    result.track = session.track();
    result.imagesWritten.insert(result.imagesWritten.begin(), result.calibration.imagesWritten.begin(),
                                result.calibration.imagesWritten.end());
    return result;
  };

  // Phase 1: the robot calibrates itself.
  result.calibrationSkipped = o.skipCalibration;
  result.calibration.truth = o.run.miscalibration;
  if (!o.skipCalibration) {
    CalibrationRunOptions run = o.run;
    run.balls = result.phaseOneBalls;
    if (o.progress) run.progress = [&](double t) { o.progress(1, t); };
    runCalibrationPhase(session, run, result.calibration);
    result.calibrationSeconds = result.calibration.phaseSeconds;
    result.calibrationWall = result.calibration.wallSeconds;
    if (!result.calibration.terminated.empty()) {
      finish();
      result.terminated = result.calibration.terminated;
      return result;
    }
  }

  // Between the phases the referee waits for the report to end (the arm comes down), then
  // places the robot again: phase 2 with the calibration the robot applied.
  session.runFor(o.placePause);
  // Phase 2: placed again, the taped balls, the shield, chest + head rear; five tasks, each
  // ended by a report and followed by the referee's tap (the clock paused in between).
  const auto wall0 = std::chrono::steady_clock::now();
  session.setShield(true);
  session.placeRobot();
  session.placeBalls(result.phaseTwoBalls);
  session.runFor(o.run.shieldSeconds);
  session.setShield(false);
  double taskStart = session.startMode(true);
  const double phaseStart = taskStart;
  if (o.progress) session.progress = [&](double t) { o.progress(2, t - phaseStart); };
  if (!o.run.imagesDir.empty()) session.keepLastViews();
  const std::array<Eigen::Vector2d, 3> spot = spots(o.run.field);
  for (int k = 0; k < 5; ++k) {
    const double deadline = session.time() + std::max(0.0, o.run.timeLimit - result.evaluationSeconds);
    const std::optional<ChallengeReport> report = session.untilReport(deadline);
    ChallengeTaskResult task;
    task.task = kTasks[k];
    const bool ballTask = k == 0 || k == 3;
    task.truth = ballTask ? Eigen::Vector2d(session.world().ballPosition(k == 0 ? 0 : 1).head<2>())
                          : spot[k == 1 ? 0 : k == 2 ? 1 : 2];
    if (!report) {
      task.simSeconds = session.time() - taskStart;
      result.evaluationSeconds += task.simSeconds;
      result.tasks.push_back(task);
      if (session.terminated().empty()) session.note("termination", "phase_time: task " + task.task + " not reported");
      break;
    }
    task.said = report->text;
    task.simSeconds = report->t - taskStart;
    result.evaluationSeconds += task.simSeconds;
    if (ballTask)
      task.reported = parseBallSentence(report->text);
    else if (!ballTask && report->text == "Finished walking")
      task.reported = Eigen::Vector2d(session.world().robotPose(0).head<2>());
    if (task.reported) task.error = (*task.reported - task.truth).norm();
    session.note("task", task.task + ": " + (task.error ? std::to_string(*task.error) + " m" : "no valid report"));
    if (!o.run.imagesDir.empty()) {
      // What the robot saw when it reported: each camera's last image with its percepts.
      for (const auto& view : session.lastViews()) {
        if (!view) continue;
        char name[96];
        std::snprintf(name, sizeof name, "/report_%d_%s_%s.png", k + 1, task.task.c_str(), cameraName(view->image.camera));
        const CameraPercepts& p = view->percepts;
        VisionResult shown;
        shown.boundary = p.fieldBoundary;
        shown.obstacles = p.obstacles;
        shown.lines = p.linesPercept();
        shown.ball = p.ball;
        shown.penaltyMarkImage = p.penaltyMarkImage;
        writePng(o.run.imagesDir + name, p.processed ? annotateVision(rgbFromCameraImage(view->image), shown, p.cameraMatrix,
                                                                      view->image.camera == CameraId::Bottom ? 2 : 1)
                                                      : rgbFromCameraImage(view->image));
        result.imagesWritten.push_back(o.run.imagesDir + name);
      }
    }
    result.tasks.push_back(task);
    if (k == 4) break;
    session.runFor(o.tapPause);
    if (!session.terminated().empty()) break;
    session.tap();
    taskStart = session.time();
  }
  session.progress = nullptr;
  result.evaluationWall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  finish();
  if (result.terminated.empty() && result.tasks.size() < 5) result.terminated = "phase_time";
  return result;
}

nlohmann::json challengeJson(const ChallengeOptions& o, const ChallengeResult& r) {
  nlohmann::json j;
  j["seed"] = o.run.seed;
  j["start"] = o.run.side > 0 ? "left" : "right";
  j["lighting"] = o.run.lighting.name;
  j["venue"] = o.venue.empty() ? nlohmann::json() : nlohmann::json(o.venue);
  j["head_id"] = r.headId;
  j["robot"] = r.robot;
  j["terminated"] = r.terminated.empty() ? nlohmann::json() : nlohmann::json(r.terminated);
  const bool calibrated = !r.calibrationSkipped;
  j["phases"] = {
      {"calibration",
       calibrated ? nlohmann::json{{"sim_s", r.calibrationSeconds},
                                   {"sim_s_rounded", roundTo(r.calibrationSeconds, 5)},
                                   {"wall_s", r.calibrationWall}}
                  : nlohmann::json{{"skipped", true}}},
      {"evaluation",
       {{"sim_s", r.evaluationSeconds}, {"sim_s_rounded", roundTo(r.evaluationSeconds, 5)}, {"wall_s", r.evaluationWall}}}};
  nlohmann::json tasks = nlohmann::json::array();
  std::map<std::string, std::optional<double>> errors;
  for (const ChallengeTaskResult& t : r.tasks) {
    tasks.push_back({{"task", t.task},
                     {"said", t.said},
                     {"reported", t.reported ? vec(*t.reported) : nlohmann::json()},
                     {"truth", vec(t.truth)},
                     {"error_m", optionalNumber(t.error)},
                     {"error_rounded_m", t.error ? nlohmann::json(roundTo(*t.error, 0.1)) : nlohmann::json()},
                     {"sim_s", t.simSeconds}});
    errors[t.task] = t.error;
  }
  j["tasks"] = tasks;
  auto rounded = [&](const char* task) {
    const auto it = errors.find(task);
    return it != errors.end() && it->second ? nlohmann::json(roundTo(*it->second, 0.1)) : nlohmann::json();
  };
  const bool allReported = r.tasks.size() == 5;
  j["categories"] = {{"calibration_time_s", calibrated ? nlohmann::json(roundTo(r.calibrationSeconds, 5)) : nlohmann::json()},
                     {"evaluation_time_s", allReported ? nlohmann::json(roundTo(r.evaluationSeconds, 5)) : nlohmann::json()},
                     {"ball_own_error_m", rounded("ball_own")},
                     {"ball_opponent_error_m", rounded("ball_opponent")},
                     {"own_goal_error_m", rounded("walk_own_goal")},
                     {"center_error_m", rounded("walk_center")},
                     {"opponent_goal_error_m", rounded("walk_opponent_goal")}};
  j["falls"] = r.falls;
  const auto truth = r.calibration.truth.toArray();
  const auto estimate = (calibrated ? r.calibration.estimate : CameraCalibration{}).toArray();
  nlohmann::json t = nlohmann::json::array(), e = nlohmann::json::array(), err = nlohmann::json::array();
  for (int k = 0; k < 6; ++k) {
    t.push_back(truth[k] / kDeg);
    e.push_back(estimate[k] / kDeg);
    err.push_back((estimate[k] - truth[k]) / kDeg);
  }
  j["offsets"] = {{"names", {"body_roll", "body_pitch", "top_roll", "top_pitch", "bottom_roll", "bottom_pitch"}},
                  {"true_deg", t},
                  {"estimated_deg", e},
                  {"error_deg", err},
                  {"applied", calibrated && r.calibration.applied}};
  j["balls"] = {{"phase1", {vec(r.phaseOneBalls[0]), vec(r.phaseOneBalls[1])}},
                {"phase2", {vec(r.phaseTwoBalls[0]), vec(r.phaseTwoBalls[1])}}};
  if (calibrated)
    j["calibration"] = {{"samples", r.calibration.samples},
                        {"views", r.calibration.views.size()},
                        {"verify_angle_deg", r.calibration.verifyAngleDeg},
                        {"reprojection_px", r.calibration.reprojectionPx}};
  j["path_m"] = r.pathLength;
  // The truth against the robot's belief once a simulated second and at the end (the pictures
  // use all of it).
  nlohmann::json track = nlohmann::json::array();
  double nextTrack = 0;
  auto pose = [](const Eigen::Vector3d& p) { return nlohmann::json{p.x(), p.y(), p.z()}; };
  for (std::size_t i = 0; i < r.track.size(); ++i) {
    const ChallengeSession::Track& k = r.track[i];
    // ... and the last one: the run ends with a report.
    if (k.t + 1e-9 < nextTrack && i + 1 < r.track.size()) continue;
    track.push_back({{"t", k.t}, {"truth", pose(k.truth)}, {"belief", pose(k.belief)}, {"valid", k.beliefValid}});
    nextTrack = std::floor(k.t + 1e-9) + 1;
  }
  j["track"] = track;
  nlohmann::json events = nlohmann::json::array();
  for (const ChallengeEvent& ev : r.events) events.push_back({{"t", ev.t}, {"kind", ev.kind}, {"text", ev.text}});
  j["events"] = events;
  return j;
}

}  // namespace nao::sim
