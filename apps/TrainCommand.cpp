// nao-soccer train ball: trains the ball classifier (perception/vision/BallClassifier.h) from
// simulated images (scenarios/BallTraining.h) and writes the model; the committed
// models/vision/ball_classifier.yml is what `nao-soccer train ball` writes with its defaults.
#include <cstdio>
#include <fstream>
#include <iostream>

#include "apps/Cli.h"
#include "apps/Commands.h"
#include "apps/SimOptions.h"
#include "robot/Error.h"
#include "robot/Paths.h"
#include "controllers/modules/BallLocator.h"
#include "scenarios/BallRoll.h"
#include "scenarios/BallTraining.h"

namespace nao::cli {

int trainBallCommand(const TrainBallOptions& options) {
  sim::BallTrainingOptions o;
  o.field = fieldFrom(options.common);
  o.scenes = options.scenes;
  o.lightingsPerScene = options.lightings;
  o.network.hidden = options.hidden;
  o.network.iterations = options.iterations;
  o.seed = options.common.seed;
  o.progress = [](int done, int total) { progress("train ball: rendering", done, total); };
  const std::string out = options.out.empty() ? dataPath("models/vision/ball_classifier.yml") : options.out;
  sim::BallSamples samples;
  const std::string& cache = options.samples;
  if (!cache.empty() && std::ifstream(cache)) {
    samples = sim::BallSamples::load(cache);
    std::fprintf(stderr, "train ball: %zu samples from %s (rendered before: --scenes, --lightings and --seed do not apply)\n",
                 samples.patches.size(), cache.c_str());
  } else {
    samples = sim::renderBallSamples(o);
    if (!cache.empty()) samples.save(cache);
  }
  const sim::BallTrainingResult r = sim::trainBallClassifier(samples, o);
  r.classifier.save(out);
  std::fprintf(stderr,
               "train ball: %d frames, %d ball / %d other samples; train accuracy %.4f; held out (%d / %d): "
               "balls %.4f, others %.4f accepted at score %.2f; wrote %s\n",
               r.frames, r.trainBalls, r.trainOthers, r.trainAccuracy, r.heldOutBalls, r.heldOutOthers,
               r.heldOutBallRate, r.heldOutFalseRate, o.threshold, out.c_str());
  nlohmann::json j = r.toJson();
  j["scenes"] = o.scenes;
  j["seed"] = o.seed;
  j["threshold"] = o.threshold;
  j["model"] = out;
  if (!options.common.json.empty()) writeJson(options.common.json, j);
  return 0;
}

// nao-soccer train friction: the ball model's constant deceleration fitted to the simulator's
// ball (scenarios/BallRoll.h). It prints the figure; config/parameters/BallLocator.json
// (filter.friction) and the code default hold what it printed (docs/modeling.md).
int trainFrictionCommand(const TrainFrictionOptions& options) {
  sim::BallRollOptions o;
  o.field = fieldFrom(options.common);
  o.rolls = options.rolls;
  o.minSpeed = options.minSpeed;
  o.maxSpeed = options.maxSpeed;
  o.seed = options.common.seed;
  o.progress = [](int done, int total) { progress("train friction: rolling", done, total); };
  const double current = modules::BallLocator::Params{}.filter.friction;
  constexpr double kPlaceholder = 0.8;  // the committed friction before the carpet's 0.30 (docs/plans/one-vs-one.md)
  const sim::BallRollFit fit = sim::fitBallRolls(o, kPlaceholder);
  nlohmann::json j = fit.toJson();
  j["seed"] = o.seed;
  j["current_friction_m_s2"] = current;
  std::fprintf(stderr, "train friction: %d rolls, friction %.4f m/s^2 (stop position error median %.3f m, max %.3f m; "
               "with %.3f m/s^2: median %.3f m)\n", o.rolls, fit.friction, j["end_error_m"]["median"].get<double>(),
               j["end_error_m"]["max"].get<double>(), kPlaceholder, j["end_error_old_m"]["median"].get<double>());
  writeJson(options.common.json.empty() ? "-" : options.common.json, j);
  return 0;
}

}  // namespace nao::cli
