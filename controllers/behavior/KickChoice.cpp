#include "controllers/behavior/KickChoice.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace nao::behavior {

namespace {

constexpr double kDeg = M_PI / 180;
constexpr double kBallRadius = 0.05;

Eigen::Vector2d along(double angle) { return {std::cos(angle), std::sin(angle)}; }

struct Interval {
  double from, to;  // rad, from < to
  double width() const { return to - from; }
};

// The goal's open intervals seen from the ball, the opponent's shadow taken out.
std::vector<Interval> openGoal(const Eigen::Vector2d& ball, const std::optional<Eigen::Vector2d>& opponent,
                               const FieldDimensions& field, double robotRadius) {
  const double x = field.length / 2 - ball.x(), half = field.goalInnerWidth / 2 - kBallRadius;
  if (x <= 0 || half <= 0) return {};
  std::vector<Interval> open{{std::atan2(-half - ball.y(), x), std::atan2(half - ball.y(), x)}};
  if (!opponent) return open;
  const Eigen::Vector2d to = *opponent - ball;
  const double d = to.norm();
  if (d < 1e-6 || opponent->x() > field.length / 2) return open;
  const double c = std::atan2(to.y(), to.x()), w = std::asin(std::min(1.0, (robotRadius + kBallRadius) / d));
  std::vector<Interval> out;
  for (const Interval& i : open) {
    if (c + w <= i.from || c - w >= i.to) {
      out.push_back(i);
      continue;
    }
    if (c - w > i.from) out.push_back({i.from, c - w});
    if (c + w < i.to) out.push_back({c + w, i.to});
  }
  return out;
}

}  // namespace

const char* kickKindName(KickChoice::Kind kind) {
  switch (kind) {
    case KickChoice::Kind::Goal: return "goal";
    case KickChoice::Kind::Half: return "half";
    case KickChoice::Kind::Advance: return "advance";
  }
  return "?";
}

KickChoice chooseKick(const Eigen::Vector2d& ball, const std::optional<Eigen::Vector2d>& opponent,
                      const FieldDimensions& field, const KickChoiceParams& p) {
  KickChoice choice;
  const Eigen::Vector2d goal(field.length / 2, 0);
  // At the goal through its widest open interval: the longest travel reaches the goal's
  // centre, the shortest the other half.
  const double halfway = field.lineWidth / 2 + kBallRadius + p.margin;
  const double toGoal = (goal - ball).norm();
  const double shortest = p.travel * (1 - p.travelSpread);
  if (toGoal <= p.travel * (1 + p.travelSpread) && ball.x() + shortest * (goal.x() - ball.x()) / toGoal >= halfway) {
    const auto open = openGoal(ball, opponent, field, p.robotRadius);
    const auto widest = std::max_element(open.begin(), open.end(),
                                         [](const Interval& a, const Interval& b) { return a.width() < b.width(); });
    if (widest != open.end() && widest->width() >= p.minOpenAngle * kDeg) {
      choice.kind = KickChoice::Kind::Goal;
      choice.direction = (widest->from + widest->to) / 2;
      choice.stop = goal;
      choice.openAngle = widest->width() / kDeg;
      return choice;
    }
  }
  const double sideY = field.width / 2 - p.margin, endX = field.length / 2 - p.margin;
  const double inGoal = field.goalInnerWidth / 2 - kBallRadius - p.margin;
  const double travels[] = {p.travel * (1 - p.travelSpread), p.travel, p.travel * (1 + p.travelSpread)};
  // Every stop the kick may give in direction `angle` (its inaccuracy, its travel spread).
  auto worst = [&](double angle, auto&& judge) {
    for (double e : {-p.inaccuracy, 0.0, p.inaccuracy})
      for (double t : travels)
        if (!judge(ball + t * along(angle + e * kDeg))) return false;
    return true;
  };
  auto inOpponentHalf = [&](const Eigen::Vector2d& s) {
    const bool goalBound = s.x() > endX && std::abs(s.y()) < inGoal;  // a goal counts too
    return s.x() >= halfway && std::abs(s.y()) <= sideY && (s.x() <= endX || goalBound);
  };
  bool found = false;
  double bestScore = -1e9;
  for (double a = -p.maxAngle; a <= p.maxAngle + 1e-9; a += p.step) {
    const double angle = a * kDeg;
    if (!worst(angle, inOpponentHalf)) continue;
    const Eigen::Vector2d stop = ball + p.travel * along(angle);
    // Far from the opponent (who may play it back), else straight ahead.
    const double score = opponent ? (stop - *opponent).norm() - 1e-3 * std::abs(a) : -std::abs(a);
    if (score > bestScore) {
      bestScore = score;
      choice.kind = KickChoice::Kind::Half;
      choice.direction = angle;
      choice.stop = stop;
      found = true;
    }
  }
  if (found) return choice;
  // Forward as far as the worst case allows, the ball kept on the field and out of the own goal.
  bestScore = -1e9;
  for (double a = -p.maxAngle; a <= p.maxAngle + 1e-9; a += p.step) {
    const double angle = a * kDeg;
    double worstX = 1e9;
    const bool onField = worst(angle, [&](const Eigen::Vector2d& s) {
      worstX = std::min(worstX, s.x());
      return std::abs(s.y()) <= sideY && s.x() >= -endX;
    });
    const double score = (onField ? 0 : -100) + worstX;
    if (score > bestScore) {
      bestScore = score;
      choice.kind = KickChoice::Kind::Advance;
      choice.direction = angle;
      choice.stop = ball + p.travel * along(angle);
    }
  }
  return choice;
}

}  // namespace nao::behavior
