// Getting up in the simulator (ground truth): pushed over onto its front or its back, lying
// still, asked to stand, the robot is upright (tilt < 20 deg, torso above 0.2 m, for 1 s)
// within 15 s -- issue 4's acceptance, a few trials per side. Labelled 'pending': the key
// frames do not yet bring the simulated robot into a squat with its centre of mass above flat
// soles (see controllers/GetUp.h), so this fails today.
#include <cmath>
#include <cstdlib>

#include <gtest/gtest.h>

#include "scenarios/GetUpEval.h"

namespace nao {
namespace {

TEST(GetUp, StandsUpWithin15SecondsFromFrontAndBack) {
  sim::GetUpEvalOptions o;
  o.trials = std::getenv("NAO_TEST_QUICK") ? 1 : 3;
  o.seed = 3;
  const sim::GetUpEvalResult r = sim::evalGetUp(o);
  ASSERT_EQ(r.sides.size(), 2u);
  for (const auto& side : r.sides) {
    std::printf("%s: %d/%d up, median %.1f s\n", side.name.c_str(), side.successes, o.trials, side.medianTime);
    EXPECT_EQ(side.successes, o.trials) << side.name;
  }
}

}  // namespace
}  // namespace nao
