// nao-soccer calibrate: the autonomous extrinsic camera calibration in the simulator, done by the
// robot program from the challenge's start (scenarios/Calibrate.h), true vs estimated offsets;
// the `eval calibration` target (many random cases) that apps/EvalCommand.cpp dispatches to; and
// `bench calibration`.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <random>

#include <unistd.h>

#include "apps/Cli.h"
#include "apps/Rows.h"
#include "apps/Commands.h"
#include "apps/SimOptions.h"
#include "controllers/CalibrationLogging.h"
#include "controllers/RobotProgram.h"
#include "controllers/modules/ModuleField.h"
#include "perception/calibration/CalibrationStore.h"
#include "robot/Parameters.h"
#include "robot/Error.h"
#include "robot/Paths.h"
#include "scenarios/Calibrate.h"
#include "scenarios/EvalRows.h"

namespace nao::cli {
namespace {

namespace cal = nao::calibration;
constexpr double kDeg = M_PI / 180;

nlohmann::json paramsDeg(const std::array<double, 6>& radians) {
  nlohmann::json j;
  for (int k = 0; k < 6; ++k) j[CameraCalibration::kNames[k]] = radians[k] / kDeg;
  return j;
}

nlohmann::json paramsValue(const std::array<double, 6>& values) {
  nlohmann::json j;
  for (int k = 0; k < 6; ++k) j[CameraCalibration::kNames[k]] = values[k];
  return j;
}

std::array<double, 6> difference(const CameraCalibration& a, const CameraCalibration& b) {
  std::array<double, 6> d{};
  const auto x = a.toArray(), y = b.toArray();
  for (int k = 0; k < 6; ++k) d[k] = x[k] - y[k];
  return d;
}

nlohmann::json runJson(const sim::CalibrationRunResult& r) {
  nlohmann::json views = nlohmann::json::array();
  for (const auto& v : r.views) {
    nlohmann::json vj = {{"camera", cameraName(v.camera)},
                         {"head_yaw_deg", v.headYawDeg},
                         {"head_pitch_deg", v.headPitchDeg},
                         {"accepted", v.accepted},
                         {"reason", v.reason},
                         {"source", v.source},
                         {"extract_ms", v.extractMs},
                         {"true_pose", {v.truePose.x(), v.truePose.y(), v.truePose.z() / kDeg}}};
    if (v.residuals)
      vj["residuals"] = {{"angle1_deg", v.residuals->angle1Deg},
                         {"angle2_deg", v.residuals->angle2Deg},
                         {"depth_m", v.residuals->depthErrorM}};
    views.push_back(vj);
  }
  nlohmann::json events = nlohmann::json::array();
  for (const auto& e : r.events) events.push_back({{"t", e.t}, {"kind", e.kind}, {"text", e.text}});
  nlohmann::json j = {{"true_deg", paramsDeg(r.truth.toArray())},
                      {"estimated_deg", paramsDeg(r.estimate.toArray())},
                      {"error_deg", paramsDeg(difference(r.estimate, r.truth))},
                      {"reprojection_px", r.reprojectionPx},
                      {"reprojection_before_px", r.reprojectionBeforePx},
                      {"reprojection_points", r.reprojectionPoints},
                      {"solve_s", r.solution.solveSeconds},
                      {"converged", r.solution.solver.converged},
                      {"iterations", r.solution.solver.iterations},
                      {"solver_message", r.solution.solver.message},
                      {"accepted", r.solution.accepted},
                      {"refusal", r.solution.reason},
                      {"residual_rms", {{"angle_deg", r.solution.rmsAngleDeg}, {"depth_m", r.solution.rmsDepthM}}},
                      {"samples", r.samples},
                      {"samples_used", r.solution.used.size()},
                      {"views", views},
                      {"head_id", r.headId},
                      {"applied", r.applied},
                      {"verify_angle_deg", r.verifyAngleDeg},
                      {"finished", r.finished},
                      {"phase_s", r.phaseSeconds},
                      {"path_m", r.pathLength},
                      {"fell", r.fell},
                      {"events", events},
                      {"wall_s", r.wallSeconds}};
  if (r.otherSolver) {
    j["other_solver"] = {{"estimated_deg", paramsDeg(r.otherSolver->x)},
                         {"converged", r.otherSolver->converged},
                         {"solve_s", r.otherSolver->seconds},
                         {"difference_deg", paramsDeg(difference(CameraCalibration::fromArray(r.otherSolver->x), r.solution.offsets))}};
  }
  return j;
}

modules::Calibrator::Params calibratorParams(const CalibrateOptions& options) {
  modules::Calibrator::Params calibrator =
      loadParams<modules::Calibrator::Params>("Calibrator", RobotProgramConfig::defaultConfigDir());
  // The robot program's own settings unless a flag says otherwise: a scorer that silently ran
  // another line source than the robot would measure another calibrator.
  if (!options.solver.empty()) calibrator.solver = options.solver;
  calibrator.compareSolvers = options.compare;
  if (!options.lines.empty()) calibrator.lines = options.lines;
  return calibrator;
}

// --save: the solution stored for the head, unless the store refuses it.
void save(const CalibrateOptions& options, const std::string& solver, const std::string& headId, const cal::CalibrationSolution& solution,
          const CameraCalibration& offsets, nlohmann::json& j) {
  const cal::CalibrationStore store(options.store);
  cal::CalibrationRecord rec;
  rec.offsets = offsets;
  rec.rmsAngleDeg = solution.rmsAngleDeg;
  rec.rmsDepthM = solution.rmsDepthM;
  rec.samples = static_cast<int>(solution.used.size());
  rec.solver = solver;
  rec.converged = solution.solver.converged && solution.accepted;
  const cal::SaveOutcome saved = store.save(headId, rec);
  j["saved"] = saved.saved;
  j["store_path"] = saved.path;
  if (!saved.saved) j["save_refused"] = saved.reason;
  std::fprintf(stderr, "calibrate: %s %s\n", saved.saved ? "saved" : "NOT saved:",
               saved.saved ? saved.path.c_str() : saved.reason.c_str());
}

// --from-log: the robot program's Calibrator on the recorded views, then its solve; no simulator.
int calibrateFromLog(const CalibrateOptions& options) {
  const cal::CalibrationLog log = cal::readCalibrationLog(options.fromLog);
  if (!options.headId.empty() && options.headId != log.headId)
    throw Error(options.fromLog, "recorded by head '" + log.headId + "', not by '" + options.headId +
                                     "' (--head-id): another robot's views calibrate that robot");
  if (log.records.empty()) throw Error(options.fromLog, "holds no views: nothing to solve from");
  ModuleContext context;
  context.configDir = RobotProgramConfig::defaultConfigDir();
  context.headId = log.headId;
  const modules::Calibrator::Params calibrator = calibratorParams(options);
  const std::string& solver = calibrator.solver;
  context.params["Calibrator"] = calibrator;
  context.params[modules::kFieldParams] = calibrationFieldFrom(options.common);
  DebugSink debug(options.debug);
  context.debug = debug.channels();
  const CalibrationReplay replay = replayCalibrationLog(log, context);
  const CalibrationStatus& s = replay.status;
  nlohmann::json views = nlohmann::json::array();
  int agree = 0;
  // The k-th accepted view gave sample k; the solve's residuals are per sample it used.
  std::map<int, const cal::SampleResiduals*> residualsOf;
  for (std::size_t u = 0; u < s.solution.used.size() && u < s.solution.residuals.size(); ++u)
    residualsOf[s.solution.used[u]] = &s.solution.residuals[u];
  int sample = 0;
  for (const ReplayedView& v : replay.views) {
    agree += v.accepted == v.liveAccepted;
    nlohmann::json view = {{"view", v.viewId}, {"camera", cameraName(v.camera)}, {"accepted", v.accepted}, {"reason", v.reason},
                           {"live_accepted", v.liveAccepted}, {"live_reason", v.liveReason}};
    if (v.accepted) {
      view["source"] = v.source;
      if (const auto it = residualsOf.find(sample); it != residualsOf.end())
        view["residuals"] = {{"angle1_deg", it->second->angle1Deg}, {"angle2_deg", it->second->angle2Deg},
                             {"parallel_deg", it->second->parallelDeg}, {"depth_m", it->second->depthErrorM}};
      ++sample;
    }
    views.push_back(view);
  }
  const auto offsets = s.offsets.toArray();
  std::fprintf(stderr, "calibrate: from %s (head %s, %s): %zu views, %d top and %d bottom samples (%d of %zu verdicts as live); "
               "%s, %s\n",
               options.fromLog.c_str(), log.headId.c_str(), log.backend.c_str(), log.records.size(), s.samples[0],
               s.samples[1], agree, replay.views.size(), s.converged ? "converged" : "did NOT converge",
               s.accepted ? "accepted" : ("NOT accepted: " + s.reason).c_str());
  for (int k = 0; k < 6; ++k)
    std::fprintf(stderr, "  %-13s estimated %+7.3f deg\n", CameraCalibration::kNames[k], offsets[k] / kDeg);
  nlohmann::json j = {{"log", options.fromLog},
                      {"head_id", log.headId},
                      {"backend", log.backend},
                      {"records", log.records.size()},
                      {"samples", {{"top", s.samples[0]}, {"bottom", s.samples[1]}}},
                      {"samples_used", s.solution.used.size()},
                      {"verdicts_as_live", agree},
                      {"estimated_deg", paramsDeg(offsets)},
                      {"converged", s.converged},
                      {"accepted", s.accepted},
                      {"refusal", s.reason},
                      {"residual_rms", {{"angle_deg", s.rmsAngleDeg}, {"depth_m", s.rmsDepthM}}},
                      {"solver", solver},
                      {"lines", calibrator.lines},
                      {"views", views}};
  if (options.save) save(options, solver, log.headId, s.solution, s.offsets, j);
  if (!options.common.json.empty()) writeJson(options.common.json, j);
  return s.accepted ? 0 : 1;
}

}  // namespace

int calibrateCommand(const CalibrateOptions& options) {
  if (!options.fromLog.empty()) return calibrateFromLog(options);
  sim::CalibrationRunOptions o;
  o.field = calibrationFieldFrom(options.common);
  o.robotModel = options.sim.model;
  o.lighting = lightingFrom(options.sim.lighting);
  o.miscalibration = miscalibrationFrom(options.sim, options.common.seed);
  o.seed = options.common.seed;
  o.venue = venueFrom(options.sim.venue).forSeed(o.seed);
  const modules::Calibrator::Params calibrator = calibratorParams(options);
  o.calibrator = calibrator;
  o.side = options.start == "left" ? 1 : -1;
  o.imagesDir = options.images;
  o.recordPath = options.record;
  o.timeLimit = options.timeLimit;
  DebugSink debug(options.debug);
  o.debug = debug.channels();
  const std::size_t limit = static_cast<std::size_t>(o.timeLimit);
  o.progress = [limit](double t) { progress("calibrate: simulated seconds of the phase", static_cast<std::size_t>(t), limit); };

  const sim::CalibrationRunResult r = sim::runCalibration(o);
  if (isatty(fileno(stderr))) std::fputc('\n', stderr);  // after the progress line
  const auto err = difference(r.estimate, r.truth);
  std::fprintf(stderr, "calibrate: %s after %.1f s (walked %.2f m); %d of %zu views gave samples, %s %s in %.3f s, %s; "
               "reprojection %.2f px (before %.2f px)\n",
               r.finished ? "reported" : "did NOT report", r.phaseSeconds, r.pathLength, r.samples, r.views.size(),
               calibrator.solver.c_str(), r.solution.solver.converged ? "converged" : "did NOT converge",
               r.solution.solveSeconds, r.applied ? "applied" : "NOT applied", r.reprojectionPx, r.reprojectionBeforePx);
  for (int k = 0; k < 6; ++k)
    std::fprintf(stderr, "  %-13s true %+7.3f  estimated %+7.3f  error %+7.3f deg\n", CameraCalibration::kNames[k],
                 r.truth.toArray()[k] / kDeg, r.estimate.toArray()[k] / kDeg, err[k] / kDeg);
  for (const auto& v : r.views)
    if (!v.accepted)
      std::fprintf(stderr, "  rejected %s yaw %+.0f: %s\n", cameraName(v.camera), v.headYawDeg, v.reason.c_str());

  nlohmann::json j = runJson(r);
  j["solver"] = calibrator.solver;
  j["lines"] = calibrator.lines;
  j["lighting"] = lightingJson(o.lighting);
  j["venue"] = sim::toJson(o.venue);
  j["seed"] = o.seed;
  j["files"] = r.imagesWritten;
  if (options.save) save(options, calibrator.solver, r.headId, r.solution, r.estimate, j);
  if (!options.common.json.empty()) writeJson(options.common.json, j);
  return r.finished && r.applied && r.solution.accepted ? 0 : 1;
}

// The aggregate of eval calibration's rows (each a trial's runJson with its seed, settings,
// lighting, venue and start side).
nlohmann::json aggregateCalibrationRows(std::vector<nlohmann::json> rows) {
  std::sort(rows.begin(), rows.end(),
            [](const nlohmann::json& a, const nlohmann::json& b) { return a.at("seed").get<std::uint64_t>() < b.at("seed").get<std::uint64_t>(); });
  std::array<std::vector<double>, 6> errors;
  std::vector<double> reprojection, solveSeconds, phaseSeconds;
  int converged = 0, accepted = 0, finished = 0;
  double agreement = 0, solveMax = 0, otherSolveMax = 0;
  const bool compare = !rows.empty() && rows.front().at("settings").at("compare_solvers").get<bool>();
  for (const nlohmann::json& r : rows) {
    const nlohmann::json* other = r.contains("other_solver") ? &r.at("other_solver") : nullptr;
    converged += r.at("converged").get<bool>() && (!compare || (other && other->at("converged").get<bool>()));
    accepted += r.at("accepted").get<bool>() && r.at("applied").get<bool>();
    finished += r.at("finished").get<bool>();
    for (int k = 0; k < 6; ++k) {
      errors[k].push_back(std::abs(r.at("error_deg").at(CameraCalibration::kNames[k]).get<double>()));
      if (other) agreement = std::max(agreement, std::abs(other->at("difference_deg").at(CameraCalibration::kNames[k]).get<double>()));
    }
    reprojection.push_back(r.at("reprojection_px").get<double>());
    solveSeconds.push_back(r.at("solve_s").get<double>());
    solveMax = std::max(solveMax, solveSeconds.back());
    if (other) otherSolveMax = std::max(otherSolveMax, other->at("solve_s").get<double>());
    phaseSeconds.push_back(r.at("phase_s").get<double>());
  }
  auto q = [](std::vector<double> v, double p) { return v.empty() ? 0.0 : sim::quantile(v, p); };
  std::array<double, 6> median{}, p95{}, max{};
  for (int k = 0; k < 6; ++k) {
    median[k] = q(errors[k], 0.5);
    p95[k] = q(errors[k], 0.95);
    max[k] = q(errors[k], 1.0);
  }
  nlohmann::json j = {{"trials", rows.size()},
                      {"converged", converged},
                      {"accepted", accepted},
                      {"finished", finished},
                      {"median_abs_error_deg", paramsValue(median)},
                      {"p95_abs_error_deg", paramsValue(p95)},
                      {"max_abs_error_deg", paramsValue(max)},
                      {"reprojection_px", {{"median", q(reprojection, 0.5)}, {"p95", q(reprojection, 0.95)}, {"max", q(reprojection, 1.0)}}},
                      {"solver_agreement_max_deg", agreement},
                      {"solve_s", {{"median", q(solveSeconds, 0.5)}, {"max", solveMax}, {"other_solver_max", otherSolveMax}}},
                      {"phase_s", {{"median", q(phaseSeconds, 0.5)}, {"max", q(phaseSeconds, 1.0)}}},
                      {"per_trial", rows}};
  if (!rows.empty()) j["settings"] = rows.front().at("settings");
  return j;
}

// eval calibration: --trials N random cases (offsets +-3 deg per parameter, a random lighting
// preset and start side), each the robot program's phase 1, its solve checked by the other
// solver; one row per trial (--rows FILE: resumable).
int evalCalibrationCommand(const EvalCalibrationOptions& options) {
  sim::CalibrationEvalOptions o;
  o.field = calibrationFieldFrom(options.common);
  o.trials = options.trials;
  o.seed = options.common.seed;
  o.lightings = lightingsFrom(options.lighting);
  o.maxOffsetDeg = options.maxOffset;
  o.timeLimit = options.timeLimit;
  o.venue = venueFrom(options.venue);
  o.randomize = options.randomize;
  o.solver = cal::parseSolver(options.solver);
  o.imagesDir = options.images;
  DebugSink debug(options.debug);
  o.debug = debug.channels();
  nlohmann::json lightings = nlohmann::json::array();
  for (const sim::Lighting& l : o.lightings) lightings.push_back(l.name);
  // What a row was drawn from: rows of other settings are refused.
  const nlohmann::json settings = {{"max_offset_deg", o.maxOffsetDeg},
                                   {"lightings", lightings},
                                   {"venue", venueJson(o.venue)},
                                   {"randomize", o.randomize},
                                   {"solver", cal::solverName(o.solver)},
                                   {"compare_solvers", o.compareSolvers},
                                   {"time_limit_s", o.timeLimit},
                                   {"robot_model", o.robotModel},
                                   {"field", {{"length", o.field.length}, {"width", o.field.width}}}};
  std::vector<nlohmann::json> done;
  if (!options.rows.empty()) done = readRows(options.rows, "eval calibration");
  RowWriter writeRow(options.rows);
  const std::vector<std::uint64_t> seeds = sim::trialSeeds(o.seed, o.trials, options.seeds, "--trials");
  nlohmann::json j = aggregateCalibrationRows(sim::collectRows(
      seeds, sim::rowsBySeed(std::move(done), settings),
      [&](std::uint64_t seed) {
        const sim::CalibrationTrial t = sim::runCalibrationTrial(o, seed);
        nlohmann::json row = runJson(t.run);
        row["seed"] = seed;
        row["settings"] = settings;
        row["lighting"] = t.lighting;
        row["venue"] = t.venue;
        row["start"] = t.side > 0 ? "left" : "right";
        return row;
      },
      [&](const nlohmann::json& row) { writeRow(row); },
      [](const nlohmann::json&, int finished, int total) { progress("eval calibration", finished, total); }));
  j["solver"] = cal::solverName(o.solver);
  j["max_offset_deg"] = o.maxOffsetDeg;
  j["seed"] = o.seed;
  j["venue"] = venueJson(o.venue);
  j["randomize"] = o.randomize;
  std::fprintf(stderr, "eval calibration: %d trials, %d converged (both solvers), %d accepted; reprojection median %.2f px, max %.2f px; GN vs Ceres <= %.4f deg; solve <= %.3f s\n",
               j["trials"].get<int>(), j["converged"].get<int>(), j["accepted"].get<int>(), j["reprojection_px"]["median"].get<double>(),
               j["reprojection_px"]["max"].get<double>(), j["solver_agreement_max_deg"].get<double>(),
               std::max(j["solve_s"]["max"].get<double>(), j["solve_s"]["other_solver_max"].get<double>()));
  for (int k = 0; k < 6; ++k)
    std::fprintf(stderr, "  %-13s median %.3f  p95 %.3f  max %.3f deg\n", CameraCalibration::kNames[k],
                 j["median_abs_error_deg"][CameraCalibration::kNames[k]].get<double>(),
                 j["p95_abs_error_deg"][CameraCalibration::kNames[k]].get<double>(),
                 j["max_abs_error_deg"][CameraCalibration::kNames[k]].get<double>());
  writeJson(options.common.json.empty() ? "-" : options.common.json, j);
  return 0;
}

// bench calibration: the time of one calibration's parts -- image to sample per camera, and the
// solve with each solver (the same samples, solved again and again; medians and maxima).
int benchCalibrationCommand(const BenchCalibrationOptions& options) {
  sim::CalibrationRunOptions o;
  o.field = calibrationFieldFrom(options.common);
  o.robotModel = options.sim.model;
  o.lighting = lightingFrom(options.sim.lighting);
  o.seed = options.common.seed;
  o.miscalibration = miscalibrationFrom(options.sim, o.seed);  // random (+-3 deg, from the seed) unless given
  o.timeLimit = options.timeLimit;
  const int repeats = options.repeats;
  checkRobotModel(o.robotModel, o.field);
  std::fprintf(stderr, "bench calibration: the robot program calibrates (phase 1)\n");
  const sim::CalibrationRunResult r = sim::runCalibration(o);
  if (r.solution.used.empty()) {
    // Nothing to time (a phase cut short by --time-limit, or no view accepted): a run that
    // missed its figures.
    std::fprintf(stderr, "bench calibration: no samples to time (%s)\n", r.solution.reason.c_str());
    writeJson(options.common.json.empty() ? "-" : options.common.json,
              {{"solve", nlohmann::json::object()}, {"samples", 0}, {"views", r.views.size()}, {"run_wall_s", r.wallSeconds},
               {"reason", r.solution.reason}, {"lighting", lightingJson(o.lighting)}, {"seed", o.seed}});
    return 1;
  }
  // The library's sample extraction, timed on the robot's own accepted views (as its Calibrator
  // ran it), each `repeats` times; the samples it used go to the solvers.
  cal::ExtractionOptions extraction;
  extraction.goalBoxDepth = o.field.goalBoxAreaLength;
  extraction.lineWidth = o.field.lineWidth;
  std::vector<cal::CalibrationSample> samples;
  std::vector<double> top, bottom;
  for (const auto& c : r.accepted) {
    std::optional<cal::CalibrationSample> sample;
    for (int i = 0; i < repeats; ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      const cal::ExtractionResult e = cal::extractSample(
          c.image, c.joints, c.imuAngle, CameraIntrinsics::fromFovY(c.image.width, c.image.height), CameraCalibration{},
          extraction);
      (c.image.camera == CameraId::Top ? top : bottom)
          .push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      sample = e.sample;
    }
    if (!sample) throw Error("calibration", "a view the robot accepted gave no sample again");
    samples.push_back(*sample);
  }
  std::vector<cal::CalibrationSample> used;
  for (int i : r.solution.used) used.push_back(samples.at(static_cast<std::size_t>(i)));
  cal::CalibratorOptions copts;
  copts.cost.goalBoxDepth = o.field.goalBoxAreaLength;
  const cal::CalibrationCost cost(used, copts.cost);
  nlohmann::json solve;
  for (cal::SolverKind kind : {cal::SolverKind::GaussNewton, cal::SolverKind::Ceres}) {
    std::vector<double> ms;
    for (int i = 0; i < 50 * repeats; ++i) ms.push_back(1000 * cal::solveWith(kind, cost, copts).seconds);
    solve[cal::solverName(kind)] = {{"median_ms", sim::quantile(ms, 0.5)}, {"max_ms", sim::quantile(ms, 1.0)}, {"runs", ms.size()}};
  }
  const nlohmann::json j = {{"solve", solve},
                            {"extract_ms", {{"top", sim::quantile(top, 0.5)}, {"bottom", sim::quantile(bottom, 0.5)}}},
                            {"samples", used.size()},
                            {"views", r.views.size()},
                            {"run_wall_s", r.wallSeconds},
                            {"lighting", lightingJson(o.lighting)},
                            {"seed", o.seed}};
  writeJson(options.common.json.empty() ? "-" : options.common.json, j);
  return 0;
}

}  // namespace nao::cli
