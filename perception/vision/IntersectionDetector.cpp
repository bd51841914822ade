#include "perception/vision/IntersectionDetector.h"

#include <cmath>

#include "perception/vision/CircleDetector.h"

namespace nao::vision {
namespace {

enum class Role { Through, End, Open, None };

// How a line relates to a point at parameter t along it (0 .. length, from `from` to `to`).
Role roleOf(const LinesPercept::Line& line, double t, double length, double margin, double maxExtension,
            const CameraMatrix& cm, const ObstaclesPercept& obstacles, double borderPx) {
  if (t < -maxExtension || t > length + maxExtension) return Role::None;
  if (t > margin && t < length - margin) return Role::Through;
  // Near an end: is that end real, or does the image (or an obstacle) cut the line there?
  const Eigen::Vector2d& endPx = t < length / 2 ? line.imageFrom : line.imageTo;
  const auto& in = cm.intrinsics;
  const bool atBorder = endPx.x() < borderPx || endPx.y() < borderPx || endPx.x() > in.width - borderPx ||
                        endPx.y() > in.height - borderPx;
  if (atBorder || obstacles.contains(endPx.x(), endPx.y())) return Role::Open;
  return Role::End;
}

// Does the line go on past the point p (ground) in direction dir? White (not field, brighter
// than the field) on most samples of its course beyond the other line's paint; too few samples
// in the image to tell counts as going on.
bool continuesBeyond(const Eigen::Vector2d& p, const Eigen::Vector2d& dir, const CameraMatrix& cm,
                     const CameraImage& image, const FieldReference& field, const IntersectionParams& params) {
  constexpr int kSamples = 5;
  int inView = 0, white = 0;
  for (int k = 0; k < kSamples; ++k) {
    const double d = params.beyondFrom + (params.beyondTo - params.beyondFrom) * k / (kSamples - 1);
    const auto q = cm.projectGround(p + d * dir);
    if (!q || !insideImage(image, q->x(), q->y(), 1)) continue;
    ++inView;
    const PixelColour c = sampleColour(image, q->x(), q->y());
    white += !field.isField(c) && c.y > field.fieldY;
  }
  return inView < 3 || white > params.maxWhiteBeyond * inView;
}

}  // namespace

std::vector<LinesPercept::Intersection> detectIntersections(const std::vector<LinesPercept::Line>& lines,
                                                             const CameraMatrix& cm,
                                                             const ObstaclesPercept& obstacles,
                                                             const IntersectionParams& params,
                                                             const CameraImage* image, const FieldReference* field) {
  std::vector<LinesPercept::Intersection> out;
  const double maxCos = std::sin(params.maxAngleErrorDeg * M_PI / 180);
  for (int i = 0; i < static_cast<int>(lines.size()); ++i)
    for (int j = i + 1; j < static_cast<int>(lines.size()); ++j) {
      const auto &a = lines[i], &b = lines[j];
      const double la = (a.to - a.from).norm(), lb = (b.to - b.from).norm();
      if (la < 1e-6 || lb < 1e-6) continue;
      const Eigen::Vector2d da = (a.to - a.from) / la, db = (b.to - b.from) / lb;
      if (std::abs(da.dot(db)) > maxCos) continue;
      const double det = da.x() * db.y() - da.y() * db.x();
      const Eigen::Vector2d r = b.from - a.from;
      const double ta = (r.x() * db.y() - r.y() * db.x()) / det;
      const double tb = (r.x() * da.y() - r.y() * da.x()) / det;
      const Eigen::Vector2d p = a.from + ta * da;
      const double margin = std::max(params.endMargin, 3 * groundSigma(cm, p));
      Role ra = roleOf(a, ta, la, margin, params.maxExtension, cm, obstacles, params.borderPx);
      Role rb = roleOf(b, tb, lb, margin, params.maxExtension, cm, obstacles, params.borderPx);
      if (image && field && field->valid) {
        // Away from the line's body: past its `to` end forwards, past its `from` end backwards.
        if (ra == Role::End && continuesBeyond(p, ta > la / 2 ? da : Eigen::Vector2d(-da), cm, *image, *field, params))
          ra = Role::Open;
        if (rb == Role::End && continuesBeyond(p, tb > lb / 2 ? db : Eigen::Vector2d(-db), cm, *image, *field, params))
          rb = Role::Open;
      }
      if (ra == Role::None || rb == Role::None) continue;
      LinesPercept::Intersection x;
      if (ra == Role::Through && rb == Role::Through) {
        x.type = LinesPercept::Intersection::Type::X;
      } else if ((ra == Role::Through && rb == Role::End) || (ra == Role::End && rb == Role::Through)) {
        x.type = LinesPercept::Intersection::Type::T;
      } else if (ra == Role::End && rb == Role::End) {
        x.type = LinesPercept::Intersection::Type::L;
      } else {
        continue;  // an open end leaves the type undecided
      }
      x.position = p;
      const auto px = cm.projectGround(p);
      x.image = px ? *px : Eigen::Vector2d(-1, -1);
      x.line1 = i;
      x.line2 = j;
      out.push_back(x);
    }
  return out;
}

}  // namespace nao::vision
