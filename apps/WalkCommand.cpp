// nao-soccer walk: walk in the simulator with a fixed speed (or to a target), report distance,
// speed, falls and the odometry's error against ground truth. Also the motion evaluations
// `eval walk`, `eval walk-to` and `eval getup` (dispatched from apps/EvalCommand.cpp).
#include <cmath>
#include <cstdio>
#include <iostream>

#include "apps/Cli.h"
#include "apps/Commands.h"
#include "apps/SimOptions.h"
#include "robot/Error.h"
#include "robot/Paths.h"
#include "scenarios/GetUpEval.h"
#include "scenarios/WalkEval.h"

namespace nao::cli {

namespace {

constexpr double kDeg = M_PI / 180;

nlohmann::json variationJson(const sim::AppliedVariation& v) {
  if (!v.randomized) return nullptr;
  nlohmann::json offsets = nlohmann::json::object();
  for (int j = 0; j < NumJoints; ++j) offsets[std::string(kJointNames[j])] = v.jointOffsets[j] / kDeg;
  return {{"total_mass_kg", v.totalMass},
          {"floor_friction", v.friction},
          {"max_joint_offset_deg", v.maxJointOffset / kDeg},
          {"joint_offsets_deg", offsets}};
}

FieldDimensions motionFieldFrom(const CommonOptions& common) {
  return common.field.empty() ? sim::motionField() : fieldFrom(common);
}

std::string jsonTarget(const CommonOptions& common) { return common.json.empty() ? "-" : common.json; }

nlohmann::json runJson(const sim::WalkRunResult& r) {
  return {{"distance_m", r.distance},
          {"mean_speed_mm_s", r.meanSpeed * 1000},
          {"forward_speed_mm_s", r.forwardSpeed * 1000},
          {"sideways_speed_mm_s", r.sidewaysSpeed * 1000},
          {"turn_rate_deg_s", r.turnRate / kDeg},
          {"falls", r.falls},
          {"odometry_error_m", r.odometryError},
          {"odometry_error_ratio", r.odometryErrorRatio},
          {"odometry_angle_error_deg", r.odometryAngleError / kDeg},
          {"max_tilt_deg", r.maxTilt / kDeg},
          {"variation", variationJson(r.variation)}};
}

}  // namespace

int walkCommand(const WalkOptions& options) {
  MotionEngine::Params params;
  DebugSink debug(options.debug);
  if (!options.to.empty()) {
    const auto& t = options.to;
    sim::WalkToOptions o;
    o.field = motionFieldFrom(options.common);
    o.target = Pose2(t[0], t[1], t[2] * kDeg);
    o.seed = options.common.seed;
    o.randomize = options.randomize;
    o.params = params;
    o.debug = debug.channels();
    const sim::WalkToResult r = sim::runWalkTo(o);
    std::fprintf(stderr, "walk to (%.2f, %.2f, %.0f deg): %s after %.1f s, error %.1f mm, %.1f deg, %d falls\n", t[0], t[1],
                 t[2], r.reached ? "reached" : "NOT reached", r.time, r.positionError * 1000, r.angleError / kDeg, r.falls);
    if (!options.common.json.empty())
      writeJson(options.common.json, {{"target", t},
                                        {"reached", r.reached},
                                        {"time_s", r.time},
                                        {"position_error_m", r.positionError},
                                        {"angle_error_deg", r.angleError / kDeg},
                                        {"odometry_position_error_m", r.odometryPositionError},
                                        {"odometry_angle_error_deg", r.odometryAngleError / kDeg},
                                        {"falls", r.falls},
                                        {"variation", variationJson(r.variation)},
                                        {"seed", o.seed}});
    return r.falls == 0 && r.reached ? 0 : 1;
  }
  sim::WalkRunOptions o;
  o.speed = Pose2(options.vx / 1000, options.vy / 1000, options.vtheta * kDeg);
  o.seconds = options.seconds;
  o.seed = options.common.seed;
  o.randomize = options.randomize;
  o.params = params;
  o.field = motionFieldFrom(options.common);
  o.debug = debug.channels();
  const sim::WalkRunResult r = sim::runWalk(o);
  std::fprintf(stderr,
               "walk %.0f s: forward %.0f mm/s, sideways %.0f mm/s, turn %.1f deg/s, %.2f m walked, %d falls, "
               "odometry error %.1f%% of the distance\n",
               o.seconds, r.forwardSpeed * 1000, r.sidewaysSpeed * 1000, r.turnRate / kDeg, r.distance, r.falls,
               r.odometryErrorRatio * 100);
  if (!options.common.json.empty()) {
    nlohmann::json j = runJson(r);
    j["command"] = {{"vx_mm_s", o.speed.x * 1000}, {"vy_mm_s", o.speed.y * 1000}, {"vtheta_deg_s", o.speed.theta / kDeg}};
    j["seconds"] = o.seconds;
    j["seed"] = o.seed;
    writeJson(options.common.json, j);
  }
  return r.falls == 0 ? 0 : 1;
}

// eval walk: random command sequences.
int evalWalkCommand(const EvalMotionOptions& options) {
  sim::WalkEvalOptions o;
  o.field = motionFieldFrom(options.common);
  o.trials = options.trials;
  o.seconds = options.seconds;
  o.seed = options.common.seed;
  o.randomize = options.randomize;
  o.progress = [](int done, int total) { progress("eval walk", done, total); };
  DebugSink debug(options.debug);
  o.debug = debug.channels();
  const sim::WalkEvalResult r = sim::evalWalk(o);
  nlohmann::json per = nlohmann::json::array();
  for (const auto& t : r.trials) per.push_back(runJson(t));
  writeJson(jsonTarget(options.common), {{"trials", o.trials},
                                    {"seconds", o.seconds},
                                    {"falls", r.falls},
                                    {"odometry_error_ratio_median", r.odometryErrorRatioMedian},
                                    {"odometry_error_ratio_max", r.odometryErrorRatioMax},
                                    {"randomized", o.randomize},
                                    {"seed", o.seed},
                                    {"per_trial", per}});
  return r.falls == 0 ? 0 : 1;
}

// eval walk-to: targets 3 m away, random direction and heading.
int evalWalkToCommand(const EvalMotionOptions& options) {
  const int trials = options.trials;
  const bool randomize = options.randomize;
  const sim::WalkToEvalResult r = sim::evalWalkTo(trials, options.common.seed, randomize, MotionEngine::Params{},
                                                  [](int done, int total) { progress("eval walk-to", done, total); });
  nlohmann::json per = nlohmann::json::array();
  for (const auto& t : r.trials)
    per.push_back({{"reached", t.reached},
                   {"target", {t.target.x, t.target.y, t.target.theta / kDeg}},
                   {"time_s", t.time},
                   {"position_error_m", t.positionError},
                   {"angle_error_deg", t.angleError / kDeg},
                   {"odometry_position_error_m", t.odometryPositionError},
                   {"odometry_offset_m", {t.odometryOffset.x(), t.odometryOffset.y()}},
                   {"odometry_angle_error_deg", t.odometryAngleError / kDeg},
                   {"control_position_error_m", t.controlPositionError},
                   {"control_angle_error_deg", t.controlAngleError / kDeg},
                   {"falls", t.falls},
                   {"variation", variationJson(t.variation)}});
  writeJson(jsonTarget(options.common), {{"trials", trials},
                                    {"falls", r.falls},
                                    {"reached", r.reached},
                                    {"position_error_median_m", r.positionErrorMedian},
                                    {"position_error_max_m", r.positionErrorMax},
                                    {"angle_error_median_deg", r.angleErrorMedian / kDeg},
                                    {"angle_error_max_deg", r.angleErrorMax / kDeg},
                                    {"odometry_position_error_median_m", r.odometryPositionErrorMedian},
                                    {"odometry_position_error_max_m", r.odometryPositionErrorMax},
                                    {"randomized", randomize},
                                    {"seed", options.common.seed},
                                    {"per_trial", per}});
  return r.falls == 0 && r.reached == trials ? 0 : 1;
}

// eval getup: lying on the front and on the back, the robot asked to stand.
int evalGetUpCommand(const EvalMotionOptions& options) {
  sim::GetUpEvalOptions o;
  o.trials = options.trials;
  o.seed = options.common.seed;
  o.randomize = options.randomize;
  o.timeLimit = options.seconds;
  o.progress = [](int done, int total) { progress("eval getup", done, total); };
  const sim::GetUpEvalResult r = sim::evalGetUp(o);
  nlohmann::json j = {{"trials", o.trials}, {"time_limit_s", o.timeLimit}, {"randomized", o.randomize}, {"seed", o.seed}};
  for (const auto& side : r.sides) {
    nlohmann::json times = nlohmann::json::array();
    for (double t : side.times) times.push_back(t);
    j[side.name] = {{"success_rate", side.successRate}, {"successes", side.successes}, {"median_time_s", side.medianTime},
                    {"times_s", times}};
  }
  writeJson(jsonTarget(options.common), j);
  bool ok = true;
  for (const auto& side : r.sides) ok = ok && side.successRate >= 0.95;
  return ok ? 0 : 1;
}

}  // namespace nao::cli
