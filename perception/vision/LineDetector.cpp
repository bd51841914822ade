#include "perception/vision/LineDetector.h"

#include "perception/vision/CircleDetector.h"

#include <algorithm>
#include <cmath>
#include <array>
#include <numeric>
#include <optional>

#include <Eigen/Eigenvalues>

namespace nao::vision {

GroundScale groundScale(const CameraMatrix& cm, const Eigen::Vector2d& pixel, double len) {
  GroundScale s;
  const auto g = cm.pixelToGround(pixel);
  if (!g) return s;
  const Eigen::Vector2d foot = cm.pose.translation().head<2>();
  Eigen::Vector2d away = *g - foot;
  if (away.norm() < 1e-6) away = cm.pose.linear().col(0).head<2>();
  if (away.norm() < 1e-9) return s;
  away.normalize();
  const Eigen::Vector2d side(-away.y(), away.x());
  const auto p0 = cm.projectGround(*g);
  const auto pa = cm.projectGround(*g + len * away);
  const auto ps = cm.projectGround(*g + len * side);
  if (!p0 || !pa || !ps) return s;
  s.valid = true;
  s.ground = *g;
  s.alongPx = (*pa - *p0).norm();
  s.acrossPx = (*ps - *p0).norm();
  return s;
}

std::pair<Eigen::Vector2d, Eigen::Vector2d> fitLineTls(const std::vector<Eigen::Vector2d>& points) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : points) cov += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
  return {mean, es.eigenvectors().col(1)};
}

namespace {

bool nearBall(const BallPercept* ball, const Eigen::Vector2d& p) {
  return ball && ball->seen && (p - ball->image).norm() < 1.3 * ball->radiusPx + 2;
}

// Is p (a white region on a horizontal scan line) part of something that rises from the field
// boundary: on the nearest vertical scan line on either side, inside the non-field region that
// starts where that line starts (a goal post's foot, a board; field lines stop short of the
// boundary)? Vertical lines ascend in x.
bool risesFromBoundary(const std::vector<ScanLine>& verticals, const Eigen::Vector2d& p) {
  auto it = std::lower_bound(verticals.begin(), verticals.end(), p.x(),
                             [](const ScanLine& sl, double x) { return sl.coord + 0.5 < x; });
  auto fromBoundary = [&](const ScanLine& sl) {
    if (sl.regions.empty()) return false;
    const ScanRegion& r = sl.regions.front();
    return r.cls != RegionClass::Field && r.from <= sl.start && p.y() < r.to + 1;
  };
  if (it != verticals.end() && fromBoundary(*it)) return true;
  return it != verticals.begin() && fromBoundary(*std::prev(it));
}

// The centre and width of a white run at half its contrast to the field beside it, from the
// luminance along the scan line (sub-pixel, blind to the blurred ramps the regions include).
bool halfContrastRun(const CameraImage& img, bool vertical, int coord, int from, int to, double& centre,
                     double& width) {
  const int n = vertical ? img.height : img.width;
  const int margin = std::clamp((to - from) / 2, 2, 6);
  const int lo = std::max(0, from - margin), hi = std::min(n - 1, to - 1 + margin);
  auto Y = [&](int i) -> double { return vertical ? img.y(coord, i) : img.y(i, coord); };
  if (from <= lo || to - 1 >= hi) return false;
  double peak = -1, baseLo = 1e9, baseHi = 1e9;
  int ip = from;
  for (int i = from; i < to; ++i)
    if (Y(i) > peak) peak = Y(i), ip = i;
  for (int i = lo; i < from; ++i) baseLo = std::min(baseLo, Y(i));
  for (int i = to; i <= hi; ++i) baseHi = std::min(baseHi, Y(i));
  const double base = 0.5 * (baseLo + baseHi);
  if (peak - base < 8) return false;
  const double level = base + 0.5 * (peak - base);
  int l = ip, r = ip;
  while (l > lo && Y(l - 1) >= level) --l;
  while (r < hi && Y(r + 1) >= level) ++r;
  if (l == lo || r == hi) return false;
  const double left = l - 0.5 + (level - Y(l - 1)) / std::max(1e-6, Y(l) - Y(l - 1));
  const double right = r + 0.5 + (Y(r) - level) / std::max(1e-6, Y(r) - Y(r + 1));
  centre = 0.5 * (left + right);
  width = right - left;
  return true;
}

// Spots on one scan line direction, grouped by scan line. crossing: the vertical scan lines
// (for the horizontal ones).
void collectSpots(const CameraImage& image, const std::vector<ScanLine>& lines, const std::vector<ScanLine>* crossing, bool vertical,
                  int imageWidth, int imageHeight, const FieldReference& field,
                  const ObstaclesPercept& obstacles,
                  const CameraMatrix& cm, const LineParams& params, const BallPercept* ball,
                  std::vector<LineSpot>& spots, std::vector<std::vector<int>>& byScan) {
  byScan.assign(lines.size(), {});
  for (int i = 0; i < static_cast<int>(lines.size()); ++i) {
    const ScanLine& sl = lines[i];
    for (std::size_t ri = 0; ri < sl.regions.size(); ++ri) {
      const ScanRegion& r = sl.regions[ri];
      if (!field.isWhiteRegion(r)) continue;
      // A white region that starts where the scan line starts (the field boundary) may be a
      // wall or a board beyond the field; one cut by the image border has an unknown middle.
      if (vertical && r.from <= sl.start) continue;
      if (r.to >= (vertical ? imageHeight : imageWidth) || (!vertical && r.from <= 0)) continue;
      double along = 0.5 * (r.from + r.to);
      double runWidth = r.to - r.from;
      Eigen::Vector2d px = vertical ? Eigen::Vector2d(sl.coord + 0.5, along) : Eigen::Vector2d(along, sl.coord + 0.5);
      if (nearBall(ball, px)) continue;
      if (!vertical && risesFromBoundary(*crossing, px)) continue;
      GroundScale gs = groundScale(cm, px, params.lineWidth);
      if (!gs.valid) continue;
      double expected = std::max(0.3, vertical ? gs.alongPx : gs.acrossPx);
      // A run wider than a line there (but not too wide for one) may be a line with soft
      // edges: the regions include its ramps, which move its middle and double its width.
      if (runWidth > params.halfContrastFactor * expected + 2 && runWidth <= params.maxThicknessFactor * expected + 2) {
        double centre = 0, width = 0;
        if (halfContrastRun(image, vertical, sl.coord, r.from, r.to, centre, width)) {
          along = centre;
          runWidth = std::min(runWidth, width);
          px = vertical ? Eigen::Vector2d(sl.coord + 0.5, along) : Eigen::Vector2d(along, sl.coord + 0.5);
          gs = groundScale(cm, px, params.lineWidth);
          if (!gs.valid) continue;
          expected = std::max(0.3, vertical ? gs.alongPx : gs.acrossPx);
        }
      }
      const double thickness = runWidth;
      if (thickness > params.maxThicknessFactor * expected + 2) continue;
      // Inside an obstacle's box only paint with field right above and below it on a vertical
      // scan line counts (a line passing behind a robot's shoulder; a robot's parts are tall).
      if (obstacles.contains(px.x(), px.y())) {
        const bool fieldAbove = ri > 0 && sl.regions[ri - 1].cls == RegionClass::Field;
        const bool fieldBelow = ri + 1 < sl.regions.size() && sl.regions[ri + 1].cls == RegionClass::Field;
        if (!vertical || !fieldAbove || !fieldBelow || thickness > 2 * expected + 2) continue;
      }
      LineSpot s;
      s.image = px;
      s.ground = gs.ground;
      s.thicknessPx = thickness;
      s.expectedPx = expected;
      s.vertical = vertical;
      s.scan = i;
      byScan[i].push_back(static_cast<int>(spots.size()));
      spots.push_back(s);
    }
  }
}

// (position along the scan line, scan coordinate) of a spot.
inline double posOf(const LineSpot& s) { return s.vertical ? s.image.y() : s.image.x(); }
inline double coordOf(const LineSpot& s) { return s.vertical ? s.image.x() : s.image.y(); }

// Chains spots on consecutive scan lines: a spot continues the chain whose extrapolation
// meets it best. "Consecutive" counts only scan lines that reach the spot's position (the
// grid's fine lines end where coarser ones take over), and one such line may be missed.
void chainSpots(const std::vector<ScanLine>& lines, const std::vector<LineSpot>& spots,
                const std::vector<std::vector<int>>& byScan, bool vertical, std::vector<SpotChain>& chains) {
  struct Chain {
    SpotChain c;
    int lastScan;
  };
  std::vector<Chain> local;
  std::vector<std::vector<int>> endingAt(byScan.size());  // chains whose last spot is on a scan line
  struct Pair {
    double err;
    int chain, spot;
  };
  std::vector<Pair> pairs;
  std::vector<int> assigned;
  for (int scan = 0; scan < static_cast<int>(byScan.size()); ++scan) {
    if (byScan[scan].empty()) continue;
    pairs.clear();
    for (int k : byScan[scan]) {
      const LineSpot& s = spots[k];
      const double p = posOf(s);
      int covering = 0;
      for (int i = scan - 1; i >= 0 && i >= scan - 64 && covering < 2; --i) {
        if (p < lines[i].start || p >= lines[i].end) continue;
        ++covering;
        for (int ci : endingAt[i]) {
          const Chain& ch = local[ci];
          if (ch.lastScan != i) continue;
          const LineSpot& last = spots[ch.c.spots.back()];
          const double dc = coordOf(s) - coordOf(last);
          if (dc <= 0) continue;
          const double dp = p - posOf(last);
          // Thickness must be alike (a line does not double its width between scan lines).
          const double t0 = last.thicknessPx, t1 = s.thicknessPx;
          if (std::max(t0, t1) > 2.5 * std::min(t0, t1) + 3) continue;
          const double tol = 1.5 + 0.5 * std::max(s.expectedPx, last.expectedPx) + (covering > 1 ? 1.0 : 0.0);
          const int n = static_cast<int>(ch.c.spots.size());
          double err;
          if (n == 1) {
            if (std::abs(dp) > 2.5 * dc + tol) continue;  // steeper than ~70 deg: the other scan direction's job
            err = std::abs(dp) / dc * 0.5 * tol;         // prefer the flattest continuation
          } else {
            const LineSpot& ref = spots[ch.c.spots[std::max(0, n - 4)]];
            const double slope = (posOf(last) - posOf(ref)) / std::max(1e-6, coordOf(last) - coordOf(ref));
            err = std::abs(posOf(last) + slope * dc - p);
            if (err > tol) continue;
          }
          pairs.push_back({err + (covering - 1) * 0.5, ci, k});
        }
      }
    }
    std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.err < b.err; });
    assigned.clear();
    for (const Pair& p : pairs) {
      Chain& ch = local[p.chain];
      if (ch.lastScan == scan || std::find(assigned.begin(), assigned.end(), p.spot) != assigned.end()) continue;
      assigned.push_back(p.spot);
      ch.c.spots.push_back(p.spot);
      ch.lastScan = scan;
      endingAt[scan].push_back(p.chain);
    }
    for (int k : byScan[scan]) {
      if (std::find(assigned.begin(), assigned.end(), k) != assigned.end()) continue;
      Chain ch;
      ch.c.vertical = vertical;
      ch.c.spots.push_back(k);
      ch.lastScan = scan;
      endingAt[scan].push_back(static_cast<int>(local.size()));
      local.push_back(std::move(ch));
    }
  }
  for (auto& ch : local)
    if (ch.c.spots.size() >= 2) chains.push_back(std::move(ch.c));
}

// Douglas-Peucker in the image: splits a chain where it deviates from the straight line
// between its ends by more than the spots' noise.
void splitStraight(const std::vector<LineSpot>& spots, const SpotChain& chain, int chainIndex, int a, int b,
                   std::vector<SpotChain>& out) {
  if (b - a + 1 < 2) return;
  const Eigen::Vector2d p = spots[chain.spots[a]].image, q = spots[chain.spots[b]].image;
  const Eigen::Vector2d d = (q - p).normalized();
  double worst = 0, expected = 0;
  int worstIdx = -1;
  for (int i = a; i <= b; ++i) {
    const Eigen::Vector2d r = spots[chain.spots[i]].image - p;
    const double dist = std::abs(r.x() * d.y() - r.y() * d.x());
    expected += spots[chain.spots[i]].expectedPx;
    if (dist > worst) worst = dist, worstIdx = i;
  }
  expected /= (b - a + 1);
  if (worst > 1.5 + 0.25 * expected && worstIdx > a && worstIdx < b) {
    splitStraight(spots, chain, chainIndex, a, worstIdx, out);
    splitStraight(spots, chain, chainIndex, worstIdx, b, out);
    return;
  }
  SpotChain s;
  s.vertical = chain.vertical;
  s.chain = chainIndex;
  s.spots.assign(chain.spots.begin() + a, chain.spots.begin() + b + 1);
  out.push_back(std::move(s));
}

}  // namespace

LineCandidates findLineCandidates(const CameraImage& image, const ScanLineRegions& regions,
                                  const FieldReference& field, const ObstaclesPercept& obstacles, const CameraMatrix& cm, const LineParams& params,
                                  const BallPercept* ball) {
  LineCandidates c;
  std::vector<std::vector<int>> byScan;
  collectSpots(image, regions.vertical, nullptr, true, image.width, image.height, field, obstacles, cm, params, ball, c.spots, byScan);
  chainSpots(regions.vertical, c.spots, byScan, true, c.chains);
  collectSpots(image, regions.horizontal, &regions.vertical, false, image.width, image.height, field, obstacles, cm, params, ball, c.spots, byScan);
  chainSpots(regions.horizontal, c.spots, byScan, false, c.chains);
  for (std::size_t i = 0; i < c.chains.size(); ++i)
    splitStraight(c.spots, c.chains[i], static_cast<int>(i), 0, static_cast<int>(c.chains[i].spots.size()) - 1,
                  c.segments);
  return c;
}

namespace {

// The contrast a line must show above the field beside it: the white test's fraction of the
// field's luminance, but no more than half the room the 8-bit sensor leaves above the field.
// Under bright light the field lies high in the range and white clips at 255; a thin line,
// blended with the grass, then rises less above the field than that fraction asks (the room
// is this image's, so no lighting is singled out).
double lineContrast(double fieldLuminance) {
  return std::max(6.0, std::min(0.18 * fieldLuminance, 0.5 * (255.0 - fieldLuminance)));
}

// The white test of one sample point on a line against one comparison point beside it (the
// paper's: brighter and less saturated than the comparison point, which is field), with the
// contrast above.
bool lineWhitePair(const PixelColour& sample, const PixelColour& comparison, const FieldReference& field) {
  return whitePair(sample, comparison, field, lineContrast(comparison.y));
}

}  // namespace

std::optional<double> whiteRatio(const CameraImage& image, const FieldReference& field, const CameraMatrix& cm,
                                 const Eigen::Vector2d& from, const Eigen::Vector2d& to, double lineWidth,
                                 const ObstaclesPercept* obstacles, double spacingPx, int maxSamples,
                                 double* paintBesideFraction) {
  const double len = (to - from).norm();
  if (len < 1e-6) return std::nullopt;
  const Eigen::Vector2d dir = (to - from) / len, normal(-dir.y(), dir.x());
  // The line's direction on the ground gives its width across the image line at each sample.
  const auto gFrom = cm.pixelToGround(from), gTo = cm.pixelToGround(to);
  Eigen::Vector2d groundNormal(0, 0);
  if (gFrom && gTo && (*gTo - *gFrom).norm() > 1e-6) {
    const Eigen::Vector2d gd = (*gTo - *gFrom).normalized();
    groundNormal = Eigen::Vector2d(-gd.y(), gd.x());
  }
  const int n = std::clamp(static_cast<int>(len / spacingPx), 2, maxSamples);
  int pairs = 0, passed = 0, counted = 0, besidePaint = 0;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d p = from + (k + 0.5) / n * (to - from);
    if (!insideImage(image, p.x(), p.y(), 1)) continue;
    if (obstacles && obstacles->contains(p.x(), p.y())) continue;
    double widthPx = 2;
    if (groundNormal.squaredNorm() > 0) {
      if (const auto g = cm.pixelToGround(p)) {
        if (const auto q = cm.projectGround(*g + lineWidth * groundNormal)) widthPx = std::abs((*q - p).dot(normal));
      }
    }
    widthPx = std::clamp(widthPx, 0.5, 200.0);
    const double off = 0.5 * widthPx + std::max(2.0, 0.75 * widthPx);
    // On a thin line a fraction of a pixel decides: take the brightest of three positions.
    PixelColour sample = sampleColour(image, p.x(), p.y());
    if (widthPx < 4) {
      for (double o : {-0.6, 0.6}) {
        const PixelColour c = sampleColour(image, p.x() + o * normal.x(), p.y() + o * normal.y());
        if (c.y > sample.y) sample = c;
      }
    }
    bool paintBeside = false;
    for (double side : {-1.0, 1.0}) {
      const Eigen::Vector2d q = p + side * off * normal;
      if (!insideImage(image, q.x(), q.y(), 1)) continue;
      const PixelColour comparison = sampleColour(image, q.x(), q.y());
      if (uninformative(comparison, field)) {
        paintBeside = true;
        continue;
      }
      ++pairs;
      passed += lineWhitePair(sample, comparison, field);
    }
    ++counted;
    besidePaint += paintBeside;
  }
  if (paintBesideFraction) *paintBesideFraction = counted ? static_cast<double>(besidePaint) / counted : 0;
  if (pairs == 0) return std::nullopt;
  return static_cast<double>(passed) / pairs;
}

namespace {

struct Merged {
  std::vector<int> spots;
  Eigen::Vector2d centre, dir;  // image TLS fit
  double tMin = 0, tMax = 0;     // extent of the spots along dir from centre
  double expected = 0;           // mean expected thickness of its spots
  bool alive = true;
  int refined = 0;               // sub-pixel centres the final fit went through (0: spots)
  std::vector<Eigen::Vector2d> refinedPoints;
};

void refit(Merged& m, const std::vector<LineSpot>& spots) {
  std::vector<Eigen::Vector2d> pts;
  pts.reserve(m.spots.size());
  double e = 0;
  for (int k : m.spots) pts.push_back(spots[k].image), e += spots[k].expectedPx;
  m.expected = e / m.spots.size();
  std::tie(m.centre, m.dir) = fitLineTls(pts);
  m.tMin = 1e9, m.tMax = -1e9;
  for (const auto& p : pts) {
    const double t = (p - m.centre).dot(m.dir);
    m.tMin = std::min(m.tMin, t), m.tMax = std::max(m.tMax, t);
  }
}

double distToLine(const Merged& m, const Eigen::Vector2d& p) {
  const Eigen::Vector2d r = p - m.centre;
  return std::abs(r.x() * m.dir.y() - r.y() * m.dir.x());
}

// The line's width across the image at p (px), from its direction on the ground.
double widthAcross(const CameraMatrix& cm, const Eigen::Vector2d& p, const Eigen::Vector2d& imageNormal,
                   const Eigen::Vector2d& groundNormal, double lineWidth) {
  const auto g = cm.pixelToGround(p);
  if (!g) return 0;
  const auto q = cm.projectGround(*g + lineWidth * groundNormal);
  return q ? std::abs((*q - p).dot(imageNormal)) : 0;
}

// The centre of a line's luminance across it at p (image normal n): the centroid of the
// luminance above the field level beside it, within a window of about the line's expected
// width. None where nothing line-like is there: too little contrast, or a window whose two
// ends differ (an object's edge, other paint inside).
std::optional<Eigen::Vector2d> centreAcross(const CameraImage& image, const CameraMatrix& cm, const Eigen::Vector2d& p,
                                            const Eigen::Vector2d& n, const Eigen::Vector2d& groundNormal,
                                            double lineWidth) {
  std::array<double, 64> profile{};
  const double w = widthAcross(cm, p, n, groundNormal, lineWidth);
  if (w <= 0) return std::nullopt;
  const double half = std::min(30.0, 0.5 * w + 2.5);
  const double step = w < 6 ? 0.5 : 1.0;
  const int count = std::min(63, static_cast<int>(2 * half / step) + 1);
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector2d q = p + (-half + i * step) * n;
    if (!insideImage(image, q.x(), q.y(), 1)) return std::nullopt;
    profile[i] = sampleColour(image, q.x(), q.y()).y;
  }
  const double base = 0.5 * (std::min(profile[0], profile[1]) + std::min(profile[count - 1], profile[count - 2]));
  double peak = 0;
  for (int i = 0; i < count; ++i) peak = std::max(peak, profile[i]);
  if (peak - base < std::min(std::max(6.0, 0.15 * base), lineContrast(base))) return std::nullopt;
  if (std::abs(profile[0] - profile[count - 1]) > 0.5 * (peak - base)) return std::nullopt;
  const double level = base + 0.3 * (peak - base);
  double sw = 0, so = 0;
  for (int i = 0; i < count; ++i) {
    const double wgt = std::max(0.0, profile[i] - level);
    sw += wgt, so += wgt * (-half + i * step);
  }
  if (sw <= 0) return std::nullopt;
  return p + (so / sw) * n;
}

// The ground direction's normal of the image segment a-b (none near the horizon).
std::optional<Eigen::Vector2d> groundNormalOf(const CameraMatrix& cm, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const auto ga = cm.pixelToGround(a), gb = cm.pixelToGround(b);
  if (!ga || !gb || (*gb - *ga).norm() < 1e-6) return std::nullopt;
  const Eigen::Vector2d gd = (*gb - *ga).normalized();
  return Eigen::Vector2d(-gd.y(), gd.x());
}

// Sub-pixel refinement: across the line at regular samples, the centroid of the luminance
// above the field level beside it; the line is refitted through these centres. Region edges
// on the scan lines are whole pixels; this is what makes short lines' directions exact.
// Returns the refined points' residual (px), or a negative value when too few samples count.
double refineAcross(const CameraImage& image, const CameraMatrix& cm, Merged& m, double lineWidth) {
  const Eigen::Vector2d a = m.centre + m.tMin * m.dir, b = m.centre + m.tMax * m.dir;
  const auto groundNormal = groundNormalOf(cm, a, b);
  if (!groundNormal) return -1;
  const Eigen::Vector2d n(-m.dir.y(), m.dir.x());
  const double len = m.tMax - m.tMin;
  const int samples = std::clamp(static_cast<int>(len / 4), 4, 40);
  std::vector<Eigen::Vector2d> centres;
  for (int k = 0; k < samples; ++k)
    if (const auto c = centreAcross(image, cm, a + (k + 0.5) / samples * (b - a), n, *groundNormal, lineWidth))
      centres.push_back(*c);
  if (centres.size() < 4) return -1;
  auto [c, d] = fitLineTls(centres);
  // One round without outliers.
  std::vector<Eigen::Vector2d> keep;
  for (const auto& p : centres) {
    const Eigen::Vector2d r = p - c;
    if (std::abs(r.x() * d.y() - r.y() * d.x()) < 1.0) keep.push_back(p);
  }
  if (keep.size() < 4) return -1;
  std::tie(c, d) = fitLineTls(keep);
  if (d.dot(m.dir) < 0) d = -d;
  double r2 = 0;
  for (const auto& p : keep) {
    const Eigen::Vector2d r = p - c;
    r2 += std::pow(r.x() * d.y() - r.y() * d.x(), 2);
  }
  // Keep the extent of the spots, measured along the refined line.
  const double t0 = (a - c).dot(d), t1 = (b - c).dot(d);
  m.centre = c;
  m.dir = d;
  m.tMin = std::min(t0, t1);
  m.tMax = std::max(t0, t1);
  m.refined = static_cast<int>(keep.size());
  m.refinedPoints = keep;
  return std::sqrt(r2 / keep.size());
}

// A short candidate followed along its own pixels beyond each end: a profile across the line
// every stepPx, centred where the line fitted so far predicts it, continues the line while
// it shows one within 1.5 px of the prediction (two misses in a row end it); the line is
// refitted through its spots and the centres found. For a line the scan grid crosses only a
// few times (a goal box's side line 2-5 m away). Returns how many centres were added.
int growAlong(const CameraImage& image, const CameraMatrix& cm, const ObstaclesPercept& obstacles,
              const std::vector<LineSpot>& spots, Merged& m, double lineWidth, double stepPx, int maxSteps) {
  std::vector<Eigen::Vector2d> points;
  for (int k : m.spots) points.push_back(spots[k].image);
  int added = 0;
  for (const double side : {-1.0, 1.0}) {
    int misses = 0;
    double t = side < 0 ? m.tMin : m.tMax;
    for (int k = 0; k < maxSteps && misses < 2; ++k) {
      t += side * stepPx;
      const Eigen::Vector2d p = m.centre + t * m.dir;
      if (!insideImage(image, p.x(), p.y(), 2) || obstacles.contains(p.x(), p.y())) break;
      const auto groundNormal = groundNormalOf(cm, m.centre + m.tMin * m.dir, m.centre + m.tMax * m.dir);
      if (!groundNormal) break;
      const Eigen::Vector2d n(-m.dir.y(), m.dir.x());
      const auto c = centreAcross(image, cm, p, n, *groundNormal, lineWidth);
      if (!c || (*c - p).norm() > 1.5) {
        ++misses;
        continue;
      }
      misses = 0;
      points.push_back(*c);
      ++added;
      Eigen::Vector2d centre, dir;
      std::tie(centre, dir) = fitLineTls(points);
      if (dir.dot(m.dir) < 0) dir = -dir;
      m.centre = centre;
      m.dir = dir;
      m.tMin = 1e9, m.tMax = -1e9;
      for (const auto& q : points) {
        const double u = (q - m.centre).dot(m.dir);
        m.tMin = std::min(m.tMin, u), m.tMax = std::max(m.tMax, u);
      }
      t = side < 0 ? m.tMin : m.tMax;
    }
  }
  return added;
}

// A chain that bends gently, always the same way, and fits the centre circle's radius on
// the ground better than a line: its straight pieces are chords of the circle, not lines
// (the circle detector may have missed the circle, e.g. when little of it is in view). An L
// or T corner bends by ~90 deg at one point and is left alone.
std::vector<char> arcChains(const LineCandidates& c, const CameraMatrix& cm, double radius) {
  std::vector<char> arc(c.chains.size(), 0);
  std::vector<std::vector<int>> pieces(c.chains.size());
  for (std::size_t s = 0; s < c.segments.size(); ++s)
    if (c.segments[s].chain >= 0) pieces[c.segments[s].chain].push_back(static_cast<int>(s));
  for (std::size_t i = 0; i < c.chains.size(); ++i) {
    if (pieces[i].size() < 2 || c.chains[i].spots.size() < 6) continue;
    // Bends between consecutive pieces, on the ground.
    double turnSign = 0;
    bool gentle = true;
    for (std::size_t k = 0; k + 1 < pieces[i].size() && gentle; ++k) {
      const auto& p = c.segments[pieces[i][k]].spots;
      const auto& q = c.segments[pieces[i][k + 1]].spots;
      const Eigen::Vector2d d0 = c.spots[p.back()].ground - c.spots[p.front()].ground;
      const Eigen::Vector2d d1 = c.spots[q.back()].ground - c.spots[q.front()].ground;
      if (d0.norm() < 1e-6 || d1.norm() < 1e-6) continue;
      const double turn = std::atan2(d0.x() * d1.y() - d0.y() * d1.x(), d0.dot(d1));
      if (std::abs(turn) > 35 * M_PI / 180 || turn * turnSign < 0) gentle = false;
      if (std::abs(turn) > 2 * M_PI / 180) turnSign = turn;
    }
    if (!gentle) continue;
    std::vector<Eigen::Vector2d> pts;
    std::vector<double> sigma;
    for (int k : c.chains[i].spots) {
      pts.push_back(c.spots[k].ground);
      sigma.push_back(groundSigma(cm, c.spots[k].ground));
    }
    arc[i] = looksLikeArc(pts, sigma, radius);
  }
  return arc;
}

}  // namespace

std::vector<LinesPercept::Line> fitLines(const LineCandidates& candidates, const std::vector<char>& excludedSpots,
                                         const CameraImage& image, const FieldReference& field,
                                         const ObstaclesPercept& obstacles, const CameraMatrix& cm,
                                         const LineParams& params, std::vector<RejectedLine>* rejected) {
  const auto& spots = candidates.spots;
  std::vector<Merged> lines;
  const std::vector<char> arc = arcChains(candidates, cm, params.circleRadius);
  for (const SpotChain& seg : candidates.segments) {
    if (seg.chain >= 0 && arc[seg.chain]) {
      if (rejected && seg.spots.size() >= 2)
        rejected->push_back({spots[seg.spots.front()].image, spots[seg.spots.back()].image,
                             static_cast<int>(seg.spots.size()), "arc chain", 0});
      continue;
    }
    int excluded = 0;
    for (int k : seg.spots) excluded += !excludedSpots.empty() && excludedSpots[k];
    if (2 * excluded >= static_cast<int>(seg.spots.size())) continue;
    Merged m;
    for (int k : seg.spots)
      if (excludedSpots.empty() || !excludedSpots[k]) m.spots.push_back(k);
    if (m.spots.size() < 2) continue;
    refit(m, spots);
    lines.push_back(std::move(m));
  }
  std::sort(lines.begin(), lines.end(), [](const Merged& a, const Merged& b) { return a.spots.size() > b.spots.size(); });

  // Merge collinear pieces (in the image, where a field line is straight whatever the
  // camera matrix) when the merged line passes the white test.
  bool changed = true;
  for (int round = 0; changed && round < 4; ++round) {
    changed = false;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (!lines[i].alive) continue;
      for (std::size_t j = i + 1; j < lines.size(); ++j) {
        Merged& a = lines[i];
        const Merged& b = lines[j];
        if (!b.alive) continue;
        const double tol = 1.5 + 0.3 * std::max(a.expected, b.expected);
        const double reach = params.mergeReach * tol;
        const Eigen::Vector2d b0 = b.centre + b.tMin * b.dir, b1 = b.centre + b.tMax * b.dir;
        const Eigen::Vector2d a0 = a.centre + a.tMin * a.dir, a1 = a.centre + a.tMax * a.dir;
        if (distToLine(a, b0) > reach || distToLine(a, b1) > reach) continue;
        // The longer piece's ends near the shorter piece's line too -- unless both pieces are
        // well measured (mergeKinkSpots each) and meet at a kink of at most mergeKinkDeg: a
        // bent line (real tape bows by 1.5-2.5 px over 500 px), whose shorter piece's
        // direction, extrapolated over the longer one, misses its far end. The merged fit's
        // residuals decide.
        const bool kink = std::min(a.spots.size(), b.spots.size()) >= static_cast<std::size_t>(params.mergeKinkSpots) &&
                          std::abs(a.dir.x() * b.dir.y() - a.dir.y() * b.dir.x()) <= std::sin(params.mergeKinkDeg * M_PI / 180);
        if (!kink && (distToLine(b, a0) > reach || distToLine(b, a1) > reach)) continue;
        Merged m = a;
        m.spots.insert(m.spots.end(), b.spots.begin(), b.spots.end());
        refit(m, spots);
        // Residual check: every spot must stay close to the merged line.
        bool fits = true;
        for (int k : m.spots)
          if (distToLine(m, spots[k].image) > tol + 0.5) {
            fits = false;
            break;
          }
        if (!fits) continue;
        // The gap between the pieces (if any) and the whole merged line must be white.
        const double ta0 = (a0 - m.centre).dot(m.dir), ta1 = (a1 - m.centre).dot(m.dir);
        const double tb0 = (b0 - m.centre).dot(m.dir), tb1 = (b1 - m.centre).dot(m.dir);
        const double gapFrom = std::min(std::max(ta0, ta1), std::max(tb0, tb1));
        const double gapTo = std::max(std::min(ta0, ta1), std::min(tb0, tb1));
        if (gapTo - gapFrom > 3) {
          const auto gap = whiteRatio(image, field, cm, m.centre + gapFrom * m.dir, m.centre + gapTo * m.dir,
                                      params.lineWidth, &obstacles, 4, 12);
          if (!gap || *gap < 0.4) continue;
          const auto whole = whiteRatio(image, field, cm, m.centre + m.tMin * m.dir, m.centre + m.tMax * m.dir,
                                        params.lineWidth, &obstacles, 6, 24);
          if (!whole || *whole < params.mergeWhiteRatio) continue;
        }
        a = std::move(m);
        lines[j].alive = false;
        changed = true;
      }
    }
  }

  std::vector<LinesPercept::Line> out;
  const Eigen::Vector2d foot = cm.pose.translation().head<2>();
  std::vector<double> residuals;
  for (Merged& m : lines) {
    if (!m.alive) continue;
    // Robust refit: spots far off the line (a piece of a crossing line at a corner) go.
    if (m.spots.size() >= 4) {
      residuals.clear();
      for (int k : m.spots) residuals.push_back(distToLine(m, spots[k].image));
      std::vector<double> sorted = residuals;
      std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
      const double limit = std::max(1.5, 3 * 1.4826 * sorted[sorted.size() / 2]);
      std::vector<int> keep;
      for (std::size_t i = 0; i < m.spots.size(); ++i)
        if (residuals[i] <= limit) keep.push_back(m.spots[i]);
      if (keep.size() < m.spots.size() && keep.size() >= 3) {
        m.spots = keep;
        refit(m, spots);
      }
    }
    // A short candidate may be a short line the scan grid crosses only a few times.
    int grown = 0;
    if (params.growStepPx > 0 && static_cast<int>(m.spots.size()) < params.minSpots && m.spots.size() >= 2)
      grown = growAlong(image, cm, obstacles, spots, m, params.lineWidth, params.growStepPx, params.growMaxSteps);
    const double refinedResidual = refineAcross(image, cm, m, params.lineWidth);
    const Eigen::Vector2d i0 = m.centre + m.tMin * m.dir, i1 = m.centre + m.tMax * m.dir;
    auto reject = [&](const char* reason, double value) {
      if (rejected) rejected->push_back({i0, i1, static_cast<int>(m.spots.size()), reason, value});
    };
    // A piece grown along a line already reported is that line again.
    if (grown > 0) {
      const bool repeated = std::any_of(out.begin(), out.end(), [&](const LinesPercept::Line& l) {
        const Eigen::Vector2d d = (l.imageTo - l.imageFrom).normalized();
        auto off = [&](const Eigen::Vector2d& p) { return std::abs(d.x() * (p.y() - l.imageFrom.y()) - d.y() * (p.x() - l.imageFrom.x())); };
        return std::abs(d.x() * m.dir.y() - d.y() * m.dir.x()) < std::sin(10 * M_PI / 180) && off(i0) < 4 + m.expected &&
               off(i1) < 4 + m.expected;
      });
      if (repeated) {
        reject("repeated", 0);
        continue;
      }
    }
    // Few spots (a short line seen end-on) suffice when the line's own pixels confirm it.
    const bool grownEnough = grown >= params.minGrown && refinedResidual >= 0;
    if (static_cast<int>(m.spots.size()) < params.minSpots && !grownEnough &&
        (static_cast<int>(m.spots.size()) < params.minSpotsRefined || refinedResidual < 0)) {
      reject("spots", static_cast<double>(m.spots.size()));
      continue;
    }
    const auto g0 = cm.pixelToGround(i0), g1 = cm.pixelToGround(i1);
    if (!g0 || !g1) {
      reject("horizon", 0);
      continue;
    }
    const double lengthM = (*g1 - *g0).norm();
    if (lengthM < params.minLengthM) {
      reject("length", lengthM);
      continue;
    }
    // Distance of the segment's nearest point from the camera's foot point.
    const Eigen::Vector2d gd = (*g1 - *g0) / lengthM;
    const double t = std::clamp((foot - *g0).dot(gd), 0.0, lengthM);
    const double nearest = (*g0 + t * gd - foot).norm();
    if (nearest > params.maxDistanceM) {
      reject("distance", nearest);
      continue;
    }
    // How well is the direction on the ground known? The fit's lateral uncertainty at the
    // ends (2 sigma / sqrt(n) for n spots spread along the line), turned in opposite
    // directions, projected to the ground.
    double sigma = 0, samples = 0;
    if (refinedResidual >= 0) {
      sigma = std::max(params.refinedSigmaPx, refinedResidual);
      samples = m.refined;
    } else {
      double res2 = 0;
      for (int k : m.spots) res2 += std::pow(distToLine(m, spots[k].image), 2);
      sigma = std::max(params.spotSigmaPx, std::sqrt(res2 / m.spots.size()));
      samples = static_cast<double>(m.spots.size());
    }
    const double endSigma = 2 * sigma / std::sqrt(samples);
    const Eigen::Vector2d imgNormal(-m.dir.y(), m.dir.x());
    const auto h0 = cm.pixelToGround(i0 + endSigma * imgNormal), h1 = cm.pixelToGround(i1 - endSigma * imgNormal);
    if (!h0 || !h1) {
      reject("horizon", 0);
      continue;
    }
    const Eigen::Vector2d gd2 = (*h1 - *h0).normalized();
    const double angleSigma = std::asin(std::min(1.0, std::abs(gd.x() * gd2.y() - gd.y() * gd2.x())));
    if (angleSigma > params.maxAngleSigmaDeg * M_PI / 180) {
      reject("angle uncertain", angleSigma * 180 / M_PI);
      continue;
    }
    // A short piece of the centre circle (tested on the sub-pixel centres where there are
    // enough, else on the spots).
    if (lengthM < 2 * params.circleRadius) {
      std::vector<std::pair<double, int>> order;
      std::vector<Eigen::Vector2d> ground;
      std::vector<double> sigmas;
      const bool useRefined = m.refined >= 6;
      const std::size_t count = useRefined ? m.refinedPoints.size() : m.spots.size();
      for (std::size_t i = 0; i < count; ++i) {
        const auto g = useRefined ? cm.pixelToGround(m.refinedPoints[i])
                                  : std::optional<Eigen::Vector2d>(spots[m.spots[i]].ground);
        if (!g) continue;
        order.emplace_back((*g - *g0).dot(gd), static_cast<int>(ground.size()));
        ground.push_back(*g);
        sigmas.push_back(groundSigma(cm, *g, useRefined ? params.refinedSigmaPx : params.spotSigmaPx));
      }
      std::sort(order.begin(), order.end());
      std::vector<Eigen::Vector2d> g2;
      std::vector<double> s2;
      for (const auto& entry : order) g2.push_back(ground[entry.second]), s2.push_back(sigmas[entry.second]);
      if (looksLikeArc(g2, s2, params.circleRadius)) {
        reject("arc", lengthM);
        continue;
      }
    }
    // Thickness: the spots' runs, turned across the line, against a line's width there.
    std::vector<double> ratios;
    const Eigen::Vector2d gn(-gd.y(), gd.x());
    const Eigen::Vector2d in(-m.dir.y(), m.dir.x());
    for (int k : m.spots) {
      const LineSpot& s = spots[k];
      const double cosine = s.vertical ? std::abs(m.dir.x()) : std::abs(m.dir.y());
      const auto q = cm.projectGround(s.ground + params.lineWidth * gn);
      if (!q) continue;
      const double expectedAcross = std::abs((*q - s.image).dot(in));
      ratios.push_back(s.thicknessPx * cosine / (2.0 * expectedAcross + 1.5));
    }
    if (ratios.empty()) {
      reject("thickness", 0);
      continue;
    }
    std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
    const bool unconfirmed = refinedResidual < 0 && static_cast<int>(m.spots.size()) < params.unrefinedSpots;
    if (ratios[ratios.size() / 2] > (unconfirmed ? params.unrefinedThickness : 1.0)) {
      reject("thickness", ratios[ratios.size() / 2]);
      continue;
    }
    double paintBeside = 0;
    const auto white = whiteRatio(image, field, cm, i0, i1, params.lineWidth, &obstacles, 6, 24, &paintBeside);
    if (!white || *white < params.lineWhiteRatio) {
      reject("white", white ? *white : -1);
      continue;
    }
    // The edge of a large bright area (a line seen from right above it, cut by the image
    // border) has paint on one side all along.
    if (paintBeside > 0.5) {
      reject("edge of paint", paintBeside);
      continue;
    }
    LinesPercept::Line line;
    line.imageFrom = i0;
    line.imageTo = i1;
    line.from = *g0;
    line.to = *g1;
    for (int k : m.spots) line.spots.push_back(spots[k].image);
    out.push_back(std::move(line));
  }
  return out;
}

}  // namespace nao::vision
