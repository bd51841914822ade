#pragma once
// Cognition: the balls lying in each half, in field coordinates (FieldBalls). Every ball
// percept seen while the robot's pose is valid becomes a field observation of the half it
// falls in; per half the densest cluster of recent observations is the ball (a false ball or
// a second ball elsewhere gathers fewer), and the newest observations of it made from near
// give the position the behaviour reports. A challenge start clears both halves.
#include <deque>

#include "representations/infrastructure/ChallengeMode.h"
#include "representations/modeling/FieldBalls.h"
#include "representations/modeling/RobotPose.h"
#include "representations/perception/CameraPercepts.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class FieldBallLocator
    : public Module<FieldBallLocator, Requires<CameraPercepts, RobotPose, ChallengeMode>, Provides<FieldBalls>,
                    Cadence::Cognition> {
 public:
  struct Params {
    double clusterRadius = 0.25;   // m: observations this near the candidate support it
    int minSupport = 5;            // observations before a cluster counts as a ball
    double maxDistance = 5.0;      // m: farther percepts are not used (their distance is poor)
    double closeDistance = 1.3;    // m: observations from this near make the reported position
    int closeSamples = 30;         // the newest this many close ones give closePosition
    int keep = 300;                // observations kept per half (the oldest go)
    double maxAge = 120.0;         // s: older observations go
    double maxPoseSigma = 0.15;    // m: no observations while the pose is less certain than this
  };
  struct Observation {
    Eigen::Vector2d field = Eigen::Vector2d::Zero();
    double distance = 0;  // m from the robot
    double time = 0;
  };

  explicit FieldBallLocator(const ModuleContext& context = {});

  // The estimate of one half from its observations (exposed for the tests).
  static FieldBalls::Ball estimate(const std::deque<Observation>& observations, const Params& params);

 private:
  void update() override;

  Params params_;
  std::deque<Observation> own_, opponent_;
  int modeId_ = 0;
  int resets_ = 0;
};

}  // namespace nao::modules

namespace nao {
template <class V>
void describe(V& v, modules::FieldBallLocator::Params& p) {
  v("clusterRadius", p.clusterRadius, 0.01, 2.0);
  v("minSupport", p.minSupport, 1, 1000);
  v("maxDistance", p.maxDistance, 0.1, 15.0);
  v("closeDistance", p.closeDistance, 0.1, 15.0);
  v("closeSamples", p.closeSamples, 1, 1000);
  v("keep", p.keep, 1, 10000);
  v("maxAge", p.maxAge, 1.0, 3600.0);
  v("maxPoseSigma", p.maxPoseSigma, 0.001, 5.0);
}
}  // namespace nao
