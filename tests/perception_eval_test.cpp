// The perception evaluation (`nao-soccer eval perception`) end to end on a few scenes: random
// poses over the field, both cameras, every lighting preset of the sweep, injected camera
// offsets, judged by the simulator's truth. A few scenes give noisy figures, so the bounds
// here are looser than issue 3's acceptance (which `eval perception --trials 300` measures);
// they catch a pipeline or a truth that has broken, and the same seed must give the same JSON.
#include <cstdio>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "perception/FieldDimensions.h"
#include "robot/Paths.h"
#include "scenarios/PerceptionEval.h"
#include "sim/Lighting.h"

namespace nao {
namespace {

sim::PerceptionEvalOptions options(int trials, std::uint64_t seed) {
  sim::PerceptionEvalOptions o;
  o.trials = trials;
  o.seed = seed;
  o.field = FieldDimensions::load(dataPath("config/field_dimensions.json"));
  o.lightings = sim::Lighting::sweep(dataPath("config/lighting.json"));
  return o;
}

TEST(PerceptionEval, LinesCircleAndBallAgainstTheTruthInEveryLight) {
  const int trials = std::getenv("NAO_TEST_QUICK") ? 4 : 10;
  const sim::PerceptionEvalOptions o = options(trials, 17);
  const sim::PerceptionEvalResult r = sim::evaluatePerception(o);
  const sim::PerceptionFigures& f = r.all;
  std::printf("frames %d: lines %d/%d found, %d/%d detections matched; balls %d/%d (3 m), %d/%d (5 m), %d false\n",
              f.frames, f.trueLinesFound, f.trueLines, f.detectedLinesMatched, f.detectedLines, f.found3, f.balls3,
              f.found5, f.balls5, f.falseBalls);
  // Every scene, both cameras, every preset.
  EXPECT_EQ(f.frames, trials * 2 * static_cast<int>(o.lightings.size()));
  ASSERT_EQ(r.byLighting.size(), o.lightings.size());
  for (const auto& l : o.lightings) EXPECT_EQ(r.byLighting.at(l.name).frames, trials * 2) << l.name;
  // The truth is there to be seen: lines in view and balls placed in front of the robot.
  ASSERT_GT(f.trueLines, 10 * trials);
  ASSERT_GT(f.balls5, 0);
  EXPECT_GE(f.lineRecall(), 0.85);
  EXPECT_GE(f.linePrecision(), 0.95);
  EXPECT_GE(f.ballRecall5(), 0.85);
  EXPECT_LE(f.falseBallsPerFrame(), 0.05);
  EXPECT_LE(f.medianBallErrorRatio(), 0.05);
  EXPECT_EQ(r.perceptionMs.size(), static_cast<std::size_t>(f.frames));
}

// The penalty cross is a landmark: a false one (a line's end, a junction or a piece of the
// circle the line detector missed) misleads the localisation. Before its surroundings were
// tested on two dense rings, 81 % of the marks seen here were false (483 in 100 scenes).
TEST(PerceptionEval, PenaltyMarksAreRealOnes) {
  sim::PerceptionEvalOptions o = options(60, 23);  // 3 s: the same under the sanitizers
  o.lightings = {sim::Lighting::parse("default", dataPath("config/lighting.json"))};
  const sim::PerceptionFigures f = sim::evaluatePerception(o).all;
  std::printf("penalty marks: %d seen, %d right; %d frames with one in view, found in %d\n", f.penaltyMarks,
              f.penaltyMarksCorrect, f.penaltyMarkFrames, f.penaltyMarkFound);
  ASSERT_GT(f.penaltyMarks, 0);
  EXPECT_GE(static_cast<double>(f.penaltyMarksCorrect) / f.penaltyMarks, 0.9);
  ASSERT_GE(f.penaltyMarkFrames, 2);
  EXPECT_GE(static_cast<double>(f.penaltyMarkFound) / f.penaltyMarkFrames, 0.75);
}

TEST(PerceptionEval, SameSeedSameFigures) {
  const auto figures = [](std::uint64_t seed) {
    nlohmann::json j = sim::evaluatePerception(options(1, seed)).toJson();
    // Timing is the machine's, not the result's.
    j.erase("perception_ms_median");
    return j.dump();
  };
  const std::string a = figures(5), b = figures(5), c = figures(6);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);  // another seed, other scenes
}

}  // namespace
}  // namespace nao
