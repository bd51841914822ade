// nao-soccer kick: kicks in the simulator, measured by ground truth (ball travel, direction
// error, falls). Each trial puts the ball 0.3-0.8 m away within +-45 deg of the robot's heading
// and asks for a kick in a direction within +-45 deg; the robot walks to the ball and kicks.
#include <cmath>
#include <cstdio>
#include <iostream>

#include "apps/Cli.h"
#include "apps/Commands.h"
#include "controllers/RobotProgram.h"
#include "controllers/modules/MotionEngineParams.h"
#include "robot/Error.h"
#include "scenarios/KickEval.h"

namespace nao::cli {

int kickCommand(const KickOptions& options) {
  sim::KickEvalOptions o;
  o.trials = options.trials;
  o.seed = options.common.seed;
  o.randomize = options.randomize;
  // The motion engine as the robot program runs it: config/parameters/MotionEngine.json.
  o.params = loadParams<MotionEngine::Params>("MotionEngine", RobotProgramConfig::defaultConfigDir());
  o.progress = [](int done, int total) { progress("kick", done, total); };
  const sim::KickEvalResult r = sim::evalKick(o);
  constexpr double kDeg = M_PI / 180;
  std::fprintf(stderr, "kick: %d trials, %d kicked, median travel %.2f m, median direction error %.1f deg, %d falls\n",
               o.trials, r.kicked, r.travelMedian, r.directionErrorMedian / kDeg, r.falls);
  if (!options.common.json.empty()) {
    nlohmann::json per = nlohmann::json::array();
    for (const auto& t : r.trials)
      per.push_back({{"kicked", t.kicked},
                     {"travel_m", t.travel},
                     {"direction_error_deg", t.directionError / kDeg},
                     {"ball_speed_m_s", t.ballSpeed},
                     {"time_s", t.time},
                     {"falls", t.falls}});
    writeJson(options.common.json, {{"trials", o.trials},
                                      {"kicked", r.kicked},
                                      {"falls", r.falls},
                                      {"ball_travel_median_m", r.travelMedian},
                                      {"direction_error_median_deg", r.directionErrorMedian / kDeg},
                                      {"randomized", o.randomize},
                                      {"seed", o.seed},
                                      {"per_trial", per}});
  }
  return r.falls == 0 && r.travelMedian >= 3.0 && r.directionErrorMedian <= 10 * kDeg ? 0 : 1;
}

}  // namespace nao::cli
