#include "perception/vision/GoalBoxDetector.h"

#include <cmath>

namespace nao::vision {
namespace {

struct Seg {
  Eigen::Vector2d a, b, dir;
  double length;
};

// How far p is from the long line's segment extended by `slack` at both ends, or a large
// value if p lies beyond that.
double joinDistance(const Eigen::Vector2d& p, const Seg& s, double slack) {
  const double t = (p - s.a).dot(s.dir);
  if (t < -slack || t > s.length + slack) return 1e9;
  const Eigen::Vector2d r = p - s.a;
  return std::abs(r.x() * s.dir.y() - r.y() * s.dir.x());
}

}  // namespace

LinesPercept::GoalBoxSide detectGoalBoxSide(const std::vector<LinesPercept::Line>& lines, int width, int height,
                                            const GoalBoxParams& params) {
  LinesPercept::GoalBoxSide best;
  std::vector<Seg> segs;
  for (const auto& l : lines) {
    Seg s{l.imageFrom, l.imageTo, Eigen::Vector2d::Zero(), (l.imageTo - l.imageFrom).norm()};
    s.dir = s.length > 0 ? Eigen::Vector2d((s.b - s.a) / s.length) : Eigen::Vector2d(1, 0);
    segs.push_back(s);
  }
  // A line cut by the image border may be longer than it looks: not a short line.
  auto atBorder = [&](const Eigen::Vector2d& p) {
    return p.x() < params.borderPx || p.y() < params.borderPx || p.x() > width - params.borderPx ||
           p.y() > height - params.borderPx;
  };
  const double minSin = std::sin(params.minAngleDeg * M_PI / 180);
  double bestShort = 1e18;
  const int n = static_cast<int>(segs.size());
  for (int s = 0; s < n; ++s) {
    const Seg& sh = segs[s];
    if (sh.length < params.minShortPx || atBorder(sh.a) || atBorder(sh.b)) continue;
    const double tol = std::max(params.joinTolerancePx, params.joinTolerance * sh.length);
    for (int i = 0; i < n; ++i) {
      if (i == s || segs[i].length < params.longRatio * sh.length) continue;
      if (std::abs(sh.dir.x() * segs[i].dir.y() - sh.dir.y() * segs[i].dir.x()) < minSin) continue;
      for (int j = 0; j < n; ++j) {
        if (j == s || j == i || segs[j].length < params.longRatio * sh.length) continue;
        if (std::abs(sh.dir.x() * segs[j].dir.y() - sh.dir.y() * segs[j].dir.x()) < minSin) continue;
        // One end of the short line on each long line.
        if (joinDistance(sh.a, segs[i], tol) > tol || joinDistance(sh.b, segs[j], tol) > tol) continue;
        if (sh.length < bestShort) {
          bestShort = sh.length;
          best.found = true;
          best.shortLine = s;
          best.longLine1 = i;
          best.longLine2 = j;
        }
      }
    }
  }
  return best;
}

}  // namespace nao::vision

namespace nao {
LinesPercept::GoalBoxSide detectGoalBoxSide(const std::vector<LinesPercept::Line>& lines, int width, int height) {
  return vision::detectGoalBoxSide(lines, width, height, vision::GoalBoxParams{});
}
}  // namespace nao
