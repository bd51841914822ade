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
#include "scenarios/BallTraining.h"

namespace nao::cli {

int trainCommand(const Argv& argv) {
  auto options = commonOptions();
  options.insert(options.end(),
                 {{"scenes", "N", "random scenes, each rendered by both cameras (default 1500; every fifth held out)"},
                  {"lightings", "N", "random lightings per scene and camera (default 2)"},
                  {"hidden", "N", "neurons in the hidden layer (default 16)"},
                  {"iterations", "N", "training epochs (default 200)"},
                  {"samples", "FILE", "reuse the rendered samples in FILE if it exists, else render and write them there"},
                  {"out", "FILE", "the model to write (default models/vision/ball_classifier.yml in the source tree)"}});
  Args args("train", argv, options, 1);
  if (args.helpRequested()) {
    std::cout << "usage: nao-soccer train ball [options]\n" << args.usage();
    return 0;
  }
  if (args.positional().empty() || args.positional()[0] != "ball") throw Error("train", "needs a target: ball");
  sim::BallTrainingOptions o;
  o.field = fieldFrom(args);
  o.scenes = static_cast<int>(args.integer("scenes", 1500));
  if (o.scenes < 5 || o.scenes > 100000) throw Error("--scenes", "must be in 5..100000");
  o.lightingsPerScene = static_cast<int>(args.integer("lightings", 2));
  if (o.lightingsPerScene < 1 || o.lightingsPerScene > 5) throw Error("--lightings", "must be in 1..5");
  o.network.hidden = static_cast<int>(args.integer("hidden", 16));
  if (o.network.hidden < 2 || o.network.hidden > 1000) throw Error("--hidden", "must be in 2..1000");
  o.network.iterations = static_cast<int>(args.integer("iterations", 200));
  if (o.network.iterations < 1 || o.network.iterations > 100000) throw Error("--iterations", "must be in 1..100000");
  o.seed = args.seed();
  o.progress = [](int done, int total) { progress("train ball: rendering", done, total); };
  const std::string out = args.str("out", dataPath("models/vision/ball_classifier.yml"));
  sim::BallSamples samples;
  const std::string cache = args.str("samples", "");
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
  if (args.has("json")) writeJson(args.str("json", "-"), j);
  return 0;
}

}  // namespace nao::cli
