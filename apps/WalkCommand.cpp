// nao-soccer walk: walk in the simulator with a fixed speed (or to a target), report distance,
// speed, falls and the odometry's error against ground truth. Also the motion evaluations
// `eval walk`, `eval walk-to` and `eval getup` (dispatched from apps/EvalCommand.cpp).
#include <cmath>
#include <cstdio>
#include <iostream>

#include "apps/Cli.h"
#include "apps/Commands.h"
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

FieldDimensions motionFieldFrom(const Args& args) {
  return args.has("field") ? FieldDimensions::load(args.str("field", "")) : sim::motionField();
}

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

std::vector<Option> motionOptions() {
  auto options = commonOptions();
  options.push_back({"randomize", "", "a 'foreign' robot: link masses +-5%, joint offsets +-1 deg, floor friction 0.6-1.0"});
  return options;
}

}  // namespace

int walkCommand(const Argv& argv) {
  auto options = motionOptions();
  options.insert(options.end(), {{"vx", "MM_S", "forward speed (default 0)"},
                                 {"vy", "MM_S", "sideways speed, left positive (default 0)"},
                                 {"vtheta", "DEG_S", "turn rate, counter-clockwise positive (default 0)"},
                                 {"seconds", "S", "how long to walk (default 10); then the robot stops"},
                                 {"to", "X,Y,THETA", "instead: walk to this robot-relative target (m, m, deg) on odometry"}});
  Args args("walk", argv, options);
  if (args.helpRequested()) {
    std::cout << args.usage();
    return 0;
  }
  MotionEngine::Params params;
  if (args.has("to")) {
    const auto t = args.list("to", 3);
    sim::WalkToOptions o;
    o.field = motionFieldFrom(args);
    o.target = Pose2(t[0], t[1], t[2] * kDeg);
    o.seed = args.seed();
    o.randomize = args.has("randomize");
    o.params = params;
    const sim::WalkToResult r = sim::runWalkTo(o);
    std::fprintf(stderr, "walk to (%.2f, %.2f, %.0f deg): %s after %.1f s, error %.1f mm, %.1f deg, %d falls\n", t[0], t[1],
                 t[2], r.reached ? "reached" : "NOT reached", r.time, r.positionError * 1000, r.angleError / kDeg, r.falls);
    if (args.has("json"))
      writeJson(args.str("json", "-"), {{"target", t},
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
  o.speed = Pose2(args.num("vx", 0) / 1000, args.num("vy", 0) / 1000, args.num("vtheta", 0) * kDeg);
  o.seconds = args.num("seconds", 10);
  if (!(o.seconds > 0 && o.seconds <= 3600)) throw Error("--seconds", "must be in (0, 3600]");
  if (!std::isfinite(o.speed.x) || !std::isfinite(o.speed.y) || !std::isfinite(o.speed.theta))
    throw Error("--vx/--vy/--vtheta", "must be finite numbers");
  o.seed = args.seed();
  o.randomize = args.has("randomize");
  o.params = params;
  o.field = motionFieldFrom(args);
  const sim::WalkRunResult r = sim::runWalk(o);
  std::fprintf(stderr,
               "walk %.0f s: forward %.0f mm/s, sideways %.0f mm/s, turn %.1f deg/s, %.2f m walked, %d falls, "
               "odometry error %.1f%% of the distance\n",
               o.seconds, r.forwardSpeed * 1000, r.sidewaysSpeed * 1000, r.turnRate / kDeg, r.distance, r.falls,
               r.odometryErrorRatio * 100);
  if (args.has("json")) {
    nlohmann::json j = runJson(r);
    j["command"] = {{"vx_mm_s", o.speed.x * 1000}, {"vy_mm_s", o.speed.y * 1000}, {"vtheta_deg_s", o.speed.theta / kDeg}};
    j["seconds"] = o.seconds;
    j["seed"] = o.seed;
    writeJson(args.str("json", "-"), j);
  }
  return r.falls == 0 ? 0 : 1;
}

// eval walk: random command sequences.
int evalWalkCommand(const Args& args) {
  sim::WalkEvalOptions o;
  o.field = motionFieldFrom(args);
  o.trials = static_cast<int>(args.integer("trials", 20));
  if (o.trials < 1 || o.trials > 10000) throw Error("--trials", "must be in 1..10000");
  o.seconds = args.num("seconds", 60);
  if (!(o.seconds > 0 && o.seconds <= 3600)) throw Error("--seconds", "must be in (0, 3600]");
  o.seed = args.seed();
  o.randomize = args.has("randomize");
  o.progress = [](int done, int total) { progress("eval walk", done, total); };
  const sim::WalkEvalResult r = sim::evalWalk(o);
  nlohmann::json per = nlohmann::json::array();
  for (const auto& t : r.trials) per.push_back(runJson(t));
  writeJson(args.str("json", "-"), {{"trials", o.trials},
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
int evalWalkToCommand(const Args& args) {
  const int trials = static_cast<int>(args.integer("trials", 20));
  if (trials < 1 || trials > 10000) throw Error("--trials", "must be in 1..10000");
  const bool randomize = args.has("randomize");
  const sim::WalkToEvalResult r = sim::evalWalkTo(trials, args.seed(), randomize, MotionEngine::Params{},
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
  writeJson(args.str("json", "-"), {{"trials", trials},
                                    {"falls", r.falls},
                                    {"reached", r.reached},
                                    {"position_error_median_m", r.positionErrorMedian},
                                    {"position_error_max_m", r.positionErrorMax},
                                    {"angle_error_median_deg", r.angleErrorMedian / kDeg},
                                    {"angle_error_max_deg", r.angleErrorMax / kDeg},
                                    {"odometry_position_error_median_m", r.odometryPositionErrorMedian},
                                    {"odometry_position_error_max_m", r.odometryPositionErrorMax},
                                    {"randomized", randomize},
                                    {"seed", args.seed()},
                                    {"per_trial", per}});
  return r.falls == 0 && r.reached == trials ? 0 : 1;
}

// eval getup: lying on the front and on the back, the robot asked to stand.
int evalGetUpCommand(const Args& args) {
  sim::GetUpEvalOptions o;
  o.trials = static_cast<int>(args.integer("trials", 20));
  if (o.trials < 1 || o.trials > 10000) throw Error("--trials", "must be in 1..10000");
  o.seed = args.seed();
  o.randomize = args.has("randomize");
  o.timeLimit = args.num("seconds", 15);
  o.progress = [](int done, int total) { progress("eval getup", done, total); };
  const sim::GetUpEvalResult r = sim::evalGetUp(o);
  nlohmann::json j = {{"trials", o.trials}, {"time_limit_s", o.timeLimit}, {"randomized", o.randomize}, {"seed", o.seed}};
  for (const auto& side : r.sides) {
    nlohmann::json times = nlohmann::json::array();
    for (double t : side.times) times.push_back(t);
    j[side.name] = {{"success_rate", side.successRate}, {"successes", side.successes}, {"median_time_s", side.medianTime},
                    {"times_s", times}};
  }
  writeJson(args.str("json", "-"), j);
  bool ok = true;
  for (const auto& side : r.sides) ok = ok && side.successRate >= 0.95;
  return ok ? 0 : 1;
}

}  // namespace nao::cli
