#include "scenarios/GetUpEval.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "robot/Error.h"
#include "scenarios/SimRun.h"
#include "sim/World.h"

namespace nao::sim {

GetUpTrialResult runGetUp(const GetUpTrialOptions& o) {
  MotionSimOptions so;
  so.seed = o.seed;
  so.randomize = o.randomize;
  so.variation = o.variation;
  so.params = o.params;
  std::mt19937_64 rng(o.seed ^ 0x9e3779b97f4a7c15ULL);
  so.pose = Eigen::Vector3d(0, 0, std::uniform_real_distribution<double>(-M_PI, M_PI)(rng));
  MotionSim sim(so);
  GetUpTrialResult r;
  r.variation = sim.variation();
  MotionRequest stand;
  const auto run = [&](double seconds, const MotionRequest& request) {
    for (int i = 0; i < static_cast<int>(std::lround(seconds / kCycleTime)); ++i)
      if (!sim.cycle(request)) throw Error("simulation", sim.stopReason());
  };
  run(o.params.transitionTime + 0.5, stand);
  // Over it goes: a push at the torso, forwards or backwards (+-25 deg), 5.5..7 N s (the stand
  // withstands 4). A robot still standing 2 s later is pushed again, 30% harder each time: every
  // trial starts lying.
  const bool front = o.side == FallDirection::Front;
  const double heading = sim.truePose().z() + (front ? 0.0 : M_PI) +
                         std::uniform_real_distribution<double>(-25, 25)(rng) * M_PI / 180;
  double impulse = std::uniform_real_distribution<double>(5.5, 7.0)(rng);
  // Lying still: asked to play dead meanwhile, so that the fall alone decides the side.
  MotionRequest lie;
  lie.motion = MotionType::PlayDead;
  for (int push = 0; push < 4 && !sim.trueFallen(); ++push, impulse *= 1.3) {
    sim.world().pushRobot(0, impulse * Eigen::Vector3d(std::cos(heading), std::sin(heading), 0));
    double stillSince = -1;
    for (int i = 0; i < static_cast<int>(6.0 / kCycleTime); ++i) {
      if (!sim.cycle(i < 30 ? stand : lie)) throw Error("simulation", sim.stopReason());
      const bool still = sim.trueFallen() && sim.frame().inertial.gyroscope.norm() < 0.2;
      if (!still) stillSince = -1;
      else if (stillSince < 0) stillSince = sim.time();
      if (stillSince >= 0 && sim.time() - stillSince > 0.5) break;
      if (i * kCycleTime > 2.0 && !sim.trueFallen()) break;  // withstood it
    }
  }
  const Eigen::Matrix3d torso = sim.world().torsoPose(0).linear();
  // Lying on the front: the torso's x axis points down.
  r.fell = sim.trueFallen();
  r.fellOnRequestedSide = r.fell && ((torso(2, 0) < 0) == front);
  const double start = sim.time();
  double uprightSince = -1;
  while (sim.time() - start < o.timeLimit + 1.0) {
    if (!sim.cycle(stand)) throw Error("simulation", sim.stopReason());
    const double z = sim.world().torsoPose(0).translation().z();
    const bool upright = sim.trueTilt() < 20 * M_PI / 180 && z > 0.2;
    if (!upright) uprightSince = -1;
    else if (uprightSince < 0) uprightSince = sim.time();
    if (uprightSince >= 0 && sim.time() - uprightSince >= 1.0) {
      r.time = uprightSince - start;
      r.success = r.fell && r.time <= o.timeLimit;
      break;
    }
  }
  r.attempts = sim.info().getUpAttempts;
  return r;
}

GetUpEvalResult evalGetUp(const GetUpEvalOptions& o) {
  if (o.trials < 1) throw Error("--trials", "must be at least 1");
  GetUpEvalResult result;
  int done = 0;
  for (FallDirection side : {FallDirection::Front, FallDirection::Back}) {
    GetUpSideResult s;
    s.name = fallDirectionName(side);
    std::vector<double> ok;
    for (int t = 0; t < o.trials; ++t) {
      GetUpTrialOptions to;
      to.side = side;
      to.timeLimit = o.timeLimit;
      to.seed = o.seed * 104729ULL + static_cast<std::uint64_t>(t) * 2 + (side == FallDirection::Back ? 1 : 0);
      to.randomize = o.randomize;
      to.variation = o.variation;
      to.params = o.params;
      const GetUpTrialResult r = runGetUp(to);
      s.times.push_back(r.success ? r.time : -1);
      if (r.success) {
        ++s.successes;
        ok.push_back(r.time);
      }
      if (o.progress) o.progress(++done, 2 * o.trials);
    }
    s.successRate = static_cast<double>(s.successes) / o.trials;
    s.medianTime = median(ok);
    result.sides.push_back(s);
  }
  return result;
}

}  // namespace nao::sim
