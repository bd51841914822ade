#pragma once
// The carpet's effect on a rolling ball, shared by the world that applies it and the
// scenarios that size kicks and rolls by it.

namespace nao::sim {

// m/s^2: a ball rolling on the carpet decelerates by this, whatever its direction
// (World::applyRollingResistance). B-Human's venue value (../shared/reference/
// localization-and-ball-model.md), the one measured carpet we know of; until 2026-12-06 it was
// 0.8, from MuJoCo's rolling friction, and the kick went half as far (docs/plans/one-vs-one.md).
constexpr double kBallRollingDeceleration = 0.3;

}  // namespace nao::sim
