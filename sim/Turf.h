#pragma once
// The carpet's effect on a rolling ball, shared by the world that applies it and the
// scenarios that size kicks and rolls by it.

namespace nao::sim {

// m/s^2: a ball rolling on the carpet decelerates by this, whatever its direction
// (World::applyRollingResistance). It came from MuJoCo's rolling friction, not from a carpet;
// B-Human's venue value is 0.30 (../shared/reference/localization-and-ball-model.md), which
// would carry the kick twice as far (docs/plans/one-vs-one.md).
constexpr double kBallRollingDeceleration = 0.8;

}  // namespace nao::sim
