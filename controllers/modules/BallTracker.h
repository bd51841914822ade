#pragma once
// Cognition: every ball the robot knows on the field (BallTracks). Each ball percept seen with
// a valid pose goes to the nearest track within reach (the track moves to it), or starts one; a
// track that should have been in the image (inside it, near enough for the vision) and was not
// seen (no ball reported, or only one clearly farther) counts a miss, and after `maxMisses` it is
// gone. When the GameController sets the game
// (SET), the referee puts the balls on the four goal free-kick positions (the 1vs1 rules):
// the tracks start there, as expected balls, and what the cameras see confirms or removes them.
#include "perception/FieldDimensions.h"
#include "representations/infrastructure/GameState.h"
#include "representations/modeling/BallTracks.h"
#include "representations/modeling/RobotPose.h"
#include "representations/perception/CameraPercepts.h"
#include "robot/Module.h"
#include "robot/Parameters.h"

namespace nao::modules {

class BallTracker : public Module<BallTracker, Requires<CameraPercepts, RobotPose, GameState>, Provides<BallTracks>,
                                  Cadence::Cognition> {
 public:
  struct Params {
    double associate = 0.4;          // m: a percept this near a track is that ball ...
    double associatePerMetre = 0.1;  // ... plus this per metre of the percept's distance
    double maxDistance = 5.0;        // m: farther percepts are not used
    double maxPoseSigma = 0.3;       // m: no percepts used while the pose is less certain
    double smoothing = 0.5;          // share of a new percept in the track's position ...
    double jitter = 0.15;            // m: ... when it is this near it (farther: the ball moved)
    int maxMisses = 6;               // images that should have shown the ball and did not ...
    double fartherBy = 0.5;          // m: ... (with a ball reported, only one this much farther)
    double expectTop = 3.5, expectBottom = 1.2;  // m: tracks nearer are expected in that camera's image
    double imageMargin = 0.1;        // of the image's size: nearer the border a ball may be cut
    int maxTracks = 8;
    double fieldMargin = 0.2;        // m: a ball seen farther off the field starts no track
  };

  explicit BallTracker(const ModuleContext& context = {});

 private:
  void update() override;

  Params params_;
  FieldDimensions field_;
  int nextId_ = 1;
  gc::State lastState_ = gc::State::Initial;
  int lastOwnScore_ = 0;
};

template <class V>
void describe(V& v, BallTracker::Params& p) {
  v("associate", p.associate, 0.01, 5.0);
  v("associatePerMetre", p.associatePerMetre, 0.0, 1.0);
  v("maxDistance", p.maxDistance, 0.1, 15.0);
  v("maxPoseSigma", p.maxPoseSigma, 0.01, 10.0);
  v("smoothing", p.smoothing, 0.0, 1.0);
  v("jitter", p.jitter, 0.0, 5.0);
  v("maxMisses", p.maxMisses, 1, 1000);
  v("fartherBy", p.fartherBy, 0.0, 10.0);
  v("expectTop", p.expectTop, 0.0, 15.0);
  v("expectBottom", p.expectBottom, 0.0, 15.0);
  v("imageMargin", p.imageMargin, 0.0, 0.5);
  v("maxTracks", p.maxTracks, 1, 100);
  v("fieldMargin", p.fieldMargin, 0.0, 5.0);
}

}  // namespace nao::modules
