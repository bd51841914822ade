#pragma once
// The striker's choice of a kick in a 1vs1 game (../shared/reference/one-vs-one.md), in the
// robot's own field frame (it attacks +x, its half is x < 0): at the goal when the goal's open
// angle, seen from the ball past the opponent, is wide enough, the longest travel reaches the
// goal and the shortest still crosses the halfway line (a short kick is then a ball in the
// other half, a long one ends in the net: a goal gives the ball back, one-vs-one.md);
// otherwise a kick whose ball stops in the opponent half for every direction within the
// kick's inaccuracy and every travel within its spread, as far from the opponent as possible;
// otherwise (the ball too deep in the own half) the kick that carries it furthest forward and
// keeps it on the field. One kick strength: the motion's kick travels about 6.6 m on the
// carpet (`kick --trials 20`; docs/plans/one-vs-one.md).
#include <optional>

#include <Eigen/Core>

#include "perception/FieldDimensions.h"

namespace nao::behavior {

struct KickChoiceParams {
  double travel = 6.6;          // m: the kick's median travel
  double travelSpread = 0.25;   // the travel varies by this share either way
  double inaccuracy = 10;       // deg: the kick's direction error assumed
  double minOpenAngle = 6;      // deg: the goal's open angle needed to kick at it
  double robotRadius = 0.15;    // m: the opponent's shadow on the goal
  double margin = 0.15;         // m: the ball's stop point this far inside the lines
  double maxAngle = 80;         // deg: directions considered either side of +x
  double step = 1;              // deg between the directions considered
};

struct KickChoice {
  enum class Kind { Goal, Half, Advance };
  Kind kind = Kind::Advance;
  double direction = 0;        // rad, field frame
  Eigen::Vector2d stop{0, 0};  // where the ball should stop (the goal's centre for Kind::Goal)
  double openAngle = 0;        // deg: the goal's widest open interval (Goal)
};

const char* kickKindName(KickChoice::Kind kind);

// ball: field frame (m); opponent: its position when known.
KickChoice chooseKick(const Eigen::Vector2d& ball, const std::optional<Eigen::Vector2d>& opponent,
                      const FieldDimensions& field, const KickChoiceParams& params = {});

template <class V>
void describe(V& v, KickChoiceParams& p) {
  v("travel", p.travel, 0.1, 10.0);
  v("travelSpread", p.travelSpread, 0.0, 0.9);
  v("inaccuracy", p.inaccuracy, 0.0, 45.0);
  v("minOpenAngle", p.minOpenAngle, 0.0, 90.0);
  v("robotRadius", p.robotRadius, 0.0, 1.0);
  v("margin", p.margin, 0.0, 1.0);
  v("maxAngle", p.maxAngle, 0.0, 180.0);
  v("step", p.step, 0.1, 30.0);
}

}  // namespace nao::behavior
