// Getting up in the simulator (ground truth): pushed over onto its front or its back, lying
// still, asked to stand, the robot is upright (tilt < 20 deg, torso above 0.2 m, for 1 s)
// within 15 s -- issue 4's acceptance, a few trials per side, for the nominal robot and for
// randomised ("foreign") robots: link masses +-5%, joint offsets +-1 deg, floor friction 0.6-1.
// NAO_TEST_QUICK runs fewer trials.
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <gtest/gtest.h>

#include "scenarios/GetUpEval.h"

namespace nao {
namespace {

void expectAllUp(bool randomize, std::uint64_t seed) {
  sim::GetUpEvalOptions o;
  o.trials = std::getenv("NAO_TEST_QUICK") ? 2 : 4;
  o.seed = seed;
  o.randomize = randomize;
  const sim::GetUpEvalResult r = sim::evalGetUp(o);
  ASSERT_EQ(r.sides.size(), 2u);
  for (const auto& side : r.sides) {
    std::printf("%s%s: %d/%d up, median %.1f s\n", randomize ? "randomised, " : "", side.name.c_str(), side.successes,
                o.trials, side.medianTime);
    EXPECT_EQ(side.successes, o.trials) << side.name;
    for (double t : side.times) EXPECT_LE(t, 15.0) << side.name;
  }
}

TEST(GetUp, StandsUpWithin15SecondsFromFrontAndBack) { expectAllUp(false, 3); }

TEST(GetUp, ForeignRobotsStandUpWithin15Seconds) { expectAllUp(true, 4); }

}  // namespace
}  // namespace nao
