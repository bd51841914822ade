#include "perception/calibration/GoalBoxFinder.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include <opencv2/imgproc.hpp>

namespace nao::calibration {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// A paint edge from LSD, oriented so that the brighter side lies on its left normal n.
struct Edge {
  Eigen::Vector2d a, b, d, n;
  double length;
};

double grayAt(const cv::Mat& gray, const Eigen::Vector2d& p) {
  const int x = std::clamp(static_cast<int>(std::floor(p.x())), 0, gray.cols - 1);
  const int y = std::clamp(static_cast<int>(std::floor(p.y())), 0, gray.rows - 1);
  return gray.at<std::uint8_t>(y, x);
}

// Where a point is along an infinite line through `a` with unit direction `d`.
double along(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& d) { return (p - a).dot(d); }

// Intersection of two infinite lines (point + direction); nullopt if parallel.
std::optional<Eigen::Vector2d> intersect(const Eigen::Vector2d& p1, const Eigen::Vector2d& d1, const Eigen::Vector2d& p2,
                                         const Eigen::Vector2d& d2) {
  const double det = cross(d1, d2);
  if (std::abs(det) < 1e-9) return std::nullopt;
  return p1 + cross(p2 - p1, d2) / det * d1;
}

}  // namespace

std::vector<ImageSegment> paintLineSegments(const cv::Mat& gray, const std::optional<ImageLine>& horizon,
                                            const SegmentOptions& o) {
  cv::Ptr<cv::LineSegmentDetector> lsd = cv::createLineSegmentDetector(cv::LSD_REFINE_STD);
  std::vector<cv::Vec4f> raw;
  lsd->detect(gray, raw);

  // Below the horizon (with a margin for the calibration error) in image terms: the horizon
  // row at a column, or nothing when the horizon is not known.
  auto belowHorizon = [&](const Eigen::Vector2d& p) {
    if (!horizon) return true;
    const Eigen::Vector2d hd = (horizon->to - horizon->from).normalized();
    // The ground is on the side of the horizon the image bottom is on.
    const Eigen::Vector2d bottom(gray.cols / 2.0, 1e6);
    const double sideBottom = cross(hd, bottom - horizon->from);
    const double side = cross(hd, p - horizon->from);
    return side * (sideBottom > 0 ? 1 : -1) > -o.horizonMarginPx;
  };

  std::vector<Edge> edges;
  for (const auto& r : raw) {
    Edge e;
    e.a = {r[0], r[1]};
    e.b = {r[2], r[3]};
    e.length = (e.b - e.a).norm();
    if (e.length < o.minEdgeLengthPx) continue;
    if (!belowHorizon(e.a) || !belowHorizon(e.b)) continue;
    e.d = (e.b - e.a) / e.length;
    e.n = {-e.d.y(), e.d.x()};
    // Which side is brighter, from a few samples along the edge.
    double left = 0, right = 0;
    for (double f : {0.25, 0.5, 0.75}) {
      const Eigen::Vector2d p = e.a + f * (e.b - e.a);
      left += grayAt(gray, p + 2.5 * e.n);
      right += grayAt(gray, p - 2.5 * e.n);
    }
    if (std::abs(left - right) < 3 * 8) continue;  // too little contrast to be a paint edge
    if (right > left) {
      std::swap(e.a, e.b);
      e.d = -e.d;
      e.n = -e.n;
    }
    edges.push_back(e);
  }

  // Antiparallel edges facing each other with their bright sides: one painted line. Each
  // pair gives a centre piece over their overlap.
  std::vector<ImageSegment> pieces;
  const double cosPair = std::cos(o.maxPairAngleDeg * kDeg);
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (std::size_t j = i + 1; j < edges.size(); ++j) {
      const Edge& ei = edges[i];
      const Edge& ej = edges[j];
      if (ei.d.dot(ej.d) > -cosPair) continue;
      const Eigen::Vector2d mi = (ei.a + ei.b) / 2, mj = (ej.a + ej.b) / 2;
      const double sij = (mj - ei.a).dot(ei.n), sji = (mi - ej.a).dot(ej.n);
      if (sij < o.minWidthPx || sij > o.maxWidthPx || sji < o.minWidthPx || sji > o.maxWidthPx) continue;
      // Overlap along ei.
      const double t0 = std::max(0.0, std::min(along(ej.a, ei.a, ei.d), along(ej.b, ei.a, ei.d)));
      const double t1 = std::min(ei.length, std::max(along(ej.a, ei.a, ei.d), along(ej.b, ei.a, ei.d)));
      const double overlap = t1 - t0;
      if (overlap < 5 || overlap < o.minOverlap * std::min(ei.length, ej.length)) continue;
      // Centre points at the overlap's ends: halfway to ej across ei.
      auto centreAt = [&](double t, double& width) {
        const Eigen::Vector2d p = ei.a + t * ei.d;
        const double u = -(p - ej.a).dot(ej.n) / ei.n.dot(ej.n);
        width = u;
        return Eigen::Vector2d(p + u / 2 * ei.n);
      };
      double w0 = 0, w1 = 0;
      const Eigen::Vector2d c0 = centreAt(t0, w0), c1 = centreAt(t1, w1);
      if (w0 < o.minWidthPx || w1 < o.minWidthPx) continue;
      // Paint between the edges: the middle brighter than both sides beyond the edges. Two
      // neighbouring lines converging in perspective also face each other with their bright
      // sides, with grass between them (seen on real frames: such a pair made a goal box).
      int bright = 0;
      constexpr int kProbes = 5;
      for (int k = 0; k < kProbes; ++k) {
        const double f = (k + 0.5) / kProbes;
        const Eigen::Vector2d c = c0 + f * (c1 - c0);
        const double w = w0 + f * (w1 - w0);
        const Eigen::Vector2d n = ei.n;
        const double outside = std::max(grayAt(gray, c + (w / 2 + 2.5) * n), grayAt(gray, c - (w / 2 + 2.5) * n));
        bright += grayAt(gray, c) >= outside + 8;
      }
      if (bright * 5 < kProbes * 3) continue;
      pieces.push_back({c0, c1, (w0 + w1) / 2});
    }

  // Merge collinear pieces (one line broken at junctions or occlusions) by union-find.
  std::vector<int> parent(pieces.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int k) {
    while (parent[k] != k) k = parent[k] = parent[parent[k]];
    return k;
  };
  const double cosMerge = std::cos(o.mergeAngleDeg * kDeg);
  for (std::size_t i = 0; i < pieces.size(); ++i)
    for (std::size_t j = i + 1; j < pieces.size(); ++j) {
      const ImageSegment& a = pieces[i];
      const ImageSegment& b = pieces[j];
      const Eigen::Vector2d da = a.direction(), db = b.direction();
      if (std::abs(da.dot(db)) < cosMerge) continue;
      const double tol = o.mergeOffsetPx + 0.3 * std::max(a.widthPx, b.widthPx);
      const Eigen::Vector2d na(-da.y(), da.x()), nb(-db.y(), db.x());
      if (std::abs((b.from - a.from).dot(na)) > tol || std::abs((b.to - a.from).dot(na)) > tol ||
          std::abs((a.from - b.from).dot(nb)) > tol || std::abs((a.to - b.from).dot(nb)) > tol)
        continue;
      parent[root(static_cast<int>(i))] = root(static_cast<int>(j));
    }
  std::vector<std::vector<int>> groups(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) groups[root(static_cast<int>(i))].push_back(static_cast<int>(i));
  std::vector<ImageSegment> lines;
  for (const auto& g : groups) {
    if (g.empty()) continue;
    // Direction: the longest piece's; extent: all pieces' ends along it; offset and width:
    // length-weighted means.
    int longest = g.front();
    for (int k : g)
      if (pieces[k].length() > pieces[longest].length()) longest = k;
    const Eigen::Vector2d d = pieces[longest].direction(), n(-d.y(), d.x());
    const Eigen::Vector2d origin = pieces[longest].from;
    double tMin = 1e30, tMax = -1e30, offset = 0, width = 0, weight = 0;
    for (int k : g) {
      const ImageSegment& p = pieces[k];
      const double len = std::max(p.length(), 1.0);
      for (const auto& q : {p.from, p.to}) {
        tMin = std::min(tMin, along(q, origin, d));
        tMax = std::max(tMax, along(q, origin, d));
        offset += len / 2 * (q - origin).dot(n);
      }
      width += len * p.widthPx;
      weight += len;
    }
    offset /= weight;
    lines.push_back({origin + tMin * d + offset * n, origin + tMax * d + offset * n, width / weight});
  }
  return lines;
}

std::vector<ImageSegment> segmentsFromLinesPercept(const std::vector<LinesPercept::Line>& lines, const CameraMatrix& cm,
                                                   double lineWidth) {
  std::vector<ImageSegment> out;
  for (const auto& l : lines) {
    ImageSegment s{l.imageFrom, l.imageTo, 4};
    // The painted width across the segment at its middle, from the (rough) projection.
    const Eigen::Vector2d mid = (l.imageFrom + l.imageTo) / 2;
    if (const auto g = cm.pixelToGround(mid)) {
      const Eigen::Vector2d dir = (l.to - l.from).normalized();
      const Eigen::Vector2d across(-dir.y(), dir.x());
      const auto a = cm.projectGround(*g + lineWidth / 2 * across);
      const auto b = cm.projectGround(*g - lineWidth / 2 * across);
      if (a && b) {
        const Eigen::Vector2d d = s.direction(), n(-d.y(), d.x());
        s.widthPx = std::max(1.5, std::abs((*a - *b).dot(n)));
      }
    }
    out.push_back(s);
  }
  return out;
}

std::vector<GoalBoxSideDetection> findGoalBoxSideCandidates(const std::vector<ImageSegment>& lines, int width,
                                                             int height, const FinderOptions& o) {
  std::vector<std::pair<double, GoalBoxSideDetection>> scored;
  const double sinMin = std::sin(o.minAngleDeg * kDeg);

  struct Join {
    int line;
    Eigen::Vector2d junction;
    double up, down;  // how far the line runs on beyond the junction, up and down the image
    double gap;       // from the short line's end to the junction
  };
  for (std::size_t s = 0; s < lines.size(); ++s) {
    const ImageSegment& S = lines[s];
    if (S.length() < o.minShortLengthPx) continue;
    const auto nearBorder = [&](const Eigen::Vector2d& p) {
      return p.x() < o.borderPx || p.y() < o.borderPx || p.x() > width - o.borderPx || p.y() > height - o.borderPx;
    };
    if (nearBorder(S.from) || nearBorder(S.to)) continue;
    const Eigen::Vector2d ds = S.direction();
    // "Up" across the short line: towards smaller rows (away from the camera on the ground).
    Eigen::Vector2d up(-ds.y(), ds.x());
    if (up.y() > 0) up = -up;
    if (std::abs(up.y()) < 0.3) continue;  // a steep "short line" is not the goal box from the side

    // Lines joining each end.
    std::vector<Join> joins[2];
    for (int end = 0; end < 2; ++end) {
      const Eigen::Vector2d e = end == 0 ? S.from : S.to;
      for (std::size_t x = 0; x < lines.size(); ++x) {
        if (x == s) continue;
        const ImageSegment& X = lines[x];
        const Eigen::Vector2d dx = X.direction();
        const double sinAngle = std::abs(cross(ds, dx));
        if (sinAngle < sinMin) continue;
        const auto j = intersect(S.from, ds, X.from, dx);
        if (!j) continue;
        // The junction is at this end of S ...
        const double gap = (*j - e).norm();
        if (gap > X.widthPx / 2 / sinAngle + S.widthPx + o.junctionSlackPx) continue;
        // ... and on X (within its extent, with slack).
        const double tj = along(*j, X.from, dx);
        const double slack = S.widthPx / sinAngle + o.junctionSlackPx;
        if (tj < -slack || tj > X.length() + slack) continue;
        // How far X runs on from the junction, up and down the image.
        const Eigen::Vector2d ux = dx.dot(up) > 0 ? dx : Eigen::Vector2d(-dx);
        const double runUp = std::max(along(X.from, *j, ux), along(X.to, *j, ux));
        const double runDown = std::max(-along(X.from, *j, ux), -along(X.to, *j, ux));
        if (std::max(runUp, runDown) < o.minRunOnPx) continue;
        joins[end].push_back({static_cast<int>(x), *j, runUp, runDown, gap});
      }
    }
    for (const Join& a : joins[0])
      for (const Join& b : joins[1]) {
        if (a.line == b.line) continue;
        // Seen from the side, the long lines run away from the camera (up the image) from the
        // short line; the goal line also runs on towards the camera, and a post may hide it
        // beyond the junction, so one of the two running up is enough.
        if (a.up < o.minRunOnPx && b.up < o.minRunOnPx) continue;
        const ImageSegment& A = lines[a.line];
        const ImageSegment& B = lines[b.line];
        // Two lines running on from either end of the short line must not cross before
        // their visible ends (they meet at the vanishing point, beyond the horizon).
        if (const auto c = intersect(A.from, A.direction(), B.from, B.direction())) {
          const double ca = (*c - a.junction).dot(up), cb = (*c - b.junction).dot(up);
          const double topA = std::max((A.from - a.junction).dot(up), (A.to - a.junction).dot(up));
          const double topB = std::max((B.from - b.junction).dot(up), (B.to - b.junction).dot(up));
          if ((ca > 0 && ca < topA) || (cb > 0 && cb < topB)) continue;
          if (ca < 0 && cb < 0) continue;  // diverging upwards: not a box seen from outside
        }
        GoalBoxSideDetection d;
        d.found = true;
        d.shortLine = S;
        d.longLine1 = A;
        d.longLine2 = B;
        d.junction1 = a.junction;
        d.junction2 = b.junction;
        const double score = S.length() + std::min(std::max(a.up, a.down), std::max(b.up, b.down)) - a.gap - b.gap;
        scored.emplace_back(score, d);
      }
  }
  std::stable_sort(scored.begin(), scored.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  std::vector<GoalBoxSideDetection> out;
  for (auto& [score, d] : scored) {
    d.candidates = static_cast<int>(scored.size());
    out.push_back(d);
  }
  return out;
}

GoalBoxSideDetection findGoalBoxSide(const std::vector<ImageSegment>& lines, int width, int height,
                                     const FinderOptions& options) {
  auto candidates = findGoalBoxSideCandidates(lines, width, height, options);
  if (!candidates.empty()) return candidates.front();
  GoalBoxSideDetection none;
  none.reason = "goal box not found: no short line joining two long lines";
  return none;
}

}  // namespace nao::calibration
