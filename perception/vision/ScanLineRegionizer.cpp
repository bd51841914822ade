#include "perception/vision/ScanLineRegionizer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "perception/vision/FieldBoundaryDetector.h"
#include "perception/vision/ObstacleDetector.h"
#include "perception/vision/Yhs.h"

namespace nao {
namespace {

// Generic constants: how many noise levels make an edge, what a green field can look like at
// all, how big "big" is, how much brighter white is. None depends on the light or the venue;
// the thresholds that do are computed from them per image.
// Edges.
constexpr double kEdgeNoiseFactor = 3.0;   // luminance edge: this many median sample differences
constexpr double kMinEdge = 4.0;           // smoothed luminance: below this nothing is an edge
constexpr double kChromaNoiseFactor = 5.0;  // colour edge (|dU| + |dV|): this many median differences
constexpr double kMinChromaEdge = 10.0;
constexpr int kCompareDistance = 3;        // px between compared samples (the smoothing kernel's width)
// Uniting regions: neighbours (and their sets' means) differ by less than this.
constexpr float kSimilarEdges = 1.0f, kSimilarY = 0.1f, kSimilarChroma = 0.25f;
// The field colour.
constexpr int kGreenHueMin = 122, kGreenHueMax = 212;  // plausible field: yellow-green to cyan-green (YHS2)
constexpr double kMinFieldChromaPerY = 0.09;           // ... with chroma / luminance at least this
constexpr double kMinFieldChroma = 3.0;
constexpr double kBigSetFraction = 0.02;   // of the scanned area: a "big" united set
constexpr double kMinSetFraction = 0.004;  // the biggest plausible set, if none is big
constexpr double kWhiterY = 1.2, kWhiterRatio = 0.75, kWhiterChroma = 1.3;  // a set "whiter" than the dominant one
constexpr double kThinSet = 3.0;           // regions on average shorter than this many line sizes: a thin set
constexpr int kHueMargin = 6;              // YHS2 hue units added to the found range
constexpr double kThickWhite = 3.0;        // a region this many line sizes long is no line (across it)
constexpr double kPaleRatio = 0.5;         // pale field: at least this fraction of the field's chroma / luminance
// Wide white (step 3c): sizes in line sizes, each allowing kLineBlurPx of blur.
constexpr float kLineBlurPx = 2.0f;        // px a line's image may grow by blur (and edge placement) on a scan line
constexpr float kWideLong = 1.5f;          // a white stretch at least this many line sizes long ...
constexpr float kWide = 2.0f;              // ... and with its crossing extent this many line widths wide is no line
// Sensor saturation: where the sensor clips, every channel reads the same maximum and
// colourless samples pile up at one luminance (a spike in the histogram, not a hump).
constexpr float kSaturatedChroma = 4.0f;   // colourless: chroma below this
constexpr double kSaturatedShare = 0.03;   // the spike holds at least this share of the scanned area
constexpr double kSaturatedSpike = 4.0;    // ... and this many times what lies just beside it
constexpr int kSaturatedMinY = 128;
constexpr float kSaturatedTolerance = 2.0f;  // luminance units about the level (sensor noise)
constexpr int kSaturatedCrossings = 2;       // a core crosses this many long saturated stretches
constexpr int kSurfaceCrossings = 12;        // a saturated surface holds this many crossings
constexpr int kSaturatedReach = 10;          // steps from a core over its blurred edges
constexpr float kSaturatedLineThick = 2.0f;  // line sizes: thinner between field is a line, clipped or not
constexpr float kNearClip = 0.05f;           // near-clipped: the brightest channel this close below the level
// White.
constexpr double kWhiteGain = 0.2;         // at least this much brighter than the field's median
constexpr double kWhiteRatio = 0.8;        // chroma / luminance below this fraction of the field's
constexpr float kLocalWhiteGain = 0.1f, kLocalWhiteEdges = 1.0f;  // local: this much brighter than the field beside it
constexpr double kLocalWhiteRatio = 0.95;  // local: chroma / luminance below the field's beside it
constexpr float kMaxWhitePoint = 0.5f;     // chroma / luminance of the white point at most (2700 K: ~0.4)
// Cleanup.
constexpr double kMinWhiteFraction = 0.35;  // of a field line's expected size: thinner white is a speck
constexpr double kGapFraction = 0.5;        // of a field line's expected size: a "small" gap

inline float chromaOf(double u, double v) {
  return static_cast<float>(std::sqrt((u - 128) * (u - 128) + (v - 128) * (v - 128)));
}

struct Sample {
  int pos;
  float y, u, v;
};

struct Pixels {
  const std::uint8_t* d;
  int W, H;
  int Y(int x, int y) const { return d[(static_cast<std::size_t>(y) * W + x) * 2]; }
  int U(int x, int y) const { return d[(static_cast<std::size_t>(y) * W + (x & ~1)) * 2 + 1]; }
  int V(int x, int y) const { return d[(static_cast<std::size_t>(y) * W + (x & ~1)) * 2 + 3]; }
};

// 3x3 Gaussian on Y; U and V (1 2 1) along the line.
Sample sampleVertical(const Pixels& p, int x, int y) {
  const int xm = std::max(x - 1, 0), xp = std::min(x + 1, p.W - 1);
  const int ym = std::max(y - 1, 0), yp = std::min(y + 1, p.H - 1);
  const int r0 = p.Y(xm, ym) + 2 * p.Y(x, ym) + p.Y(xp, ym);
  const int r1 = p.Y(xm, y) + 2 * p.Y(x, y) + p.Y(xp, y);
  const int r2 = p.Y(xm, yp) + 2 * p.Y(x, yp) + p.Y(xp, yp);
  return {y, (r0 + 2 * r1 + r2) / 16.f, (p.U(x, ym) + 2 * p.U(x, y) + p.U(x, yp)) / 4.f,
          (p.V(x, ym) + 2 * p.V(x, y) + p.V(x, yp)) / 4.f};
}
Sample sampleHorizontal(const Pixels& p, int x, int y) {
  const int xm = std::max(x - 1, 0), xp = std::min(x + 1, p.W - 1);
  const int ym = std::max(y - 1, 0), yp = std::min(y + 1, p.H - 1);
  const int c0 = p.Y(xm, ym) + 2 * p.Y(xm, y) + p.Y(xm, yp);
  const int c1 = p.Y(x, ym) + 2 * p.Y(x, y) + p.Y(x, yp);
  const int c2 = p.Y(xp, ym) + 2 * p.Y(xp, y) + p.Y(xp, yp);
  return {x, (c0 + 2 * c1 + c2) / 16.f, (p.U(xm, y) + 2 * p.U(x, y) + p.U(xp, y)) / 4.f,
          (p.V(xm, y) + 2 * p.V(x, y) + p.V(xp, y)) / 4.f};
}
// Sobel-type derivative (1 2 1 across, -1 1 along) between pixel q - 1 and q of a line.
int derivVertical(const Pixels& p, int x, int q) {
  const int xm = std::max(x - 1, 0), xp = std::min(x + 1, p.W - 1);
  return (p.Y(xm, q) + 2 * p.Y(x, q) + p.Y(xp, q)) - (p.Y(xm, q - 1) + 2 * p.Y(x, q - 1) + p.Y(xp, q - 1));
}
int derivHorizontal(const Pixels& p, int q, int y) {
  const int ym = std::max(y - 1, 0), yp = std::min(y + 1, p.H - 1);
  return (p.Y(q, ym) + 2 * p.Y(q, y) + p.Y(q, yp)) - (p.Y(q - 1, ym) + 2 * p.Y(q - 1, y) + p.Y(q - 1, yp));
}
int chromaDerivVertical(const Pixels& p, int x, int q) {
  return std::abs(p.U(x, q) - p.U(x, q - 1)) + std::abs(p.V(x, q) - p.V(x, q - 1));
}
int chromaDerivHorizontal(const Pixels& p, int q, int y) {
  // U/V change only between pixel pairs: compare the pairs around q.
  const int a = std::max(q - 2, 0);
  return std::abs(p.U(q, y) - p.U(a, y)) + std::abs(p.V(q, y) - p.V(a, y));
}

// Per region, what classification needs (mean colour as floats and the region's weight).
struct RegionStats {
  float y, u, v;
  float chroma;  // hypot(u - 128, v - 128)
  float area;    // length x the line's share of the image
  float thick;   // length / the expected size of a field line there
};

// Area-weighted colour sums of a united set.
struct SetSum {
  double area = 0, y = 0, u = 0, v = 0;
  void add(const SetSum& o) { area += o.area, y += o.y, u += o.u, v += o.v; }
  RegionStats mean() const {
    const float a = static_cast<float>(std::max(area, 1e-9));
    const float my = static_cast<float>(y) / a, mu = static_cast<float>(u) / a, mv = static_cast<float>(v) / a;
    return {my, mu, mv, chromaOf(mu, mv), a, 0};
  }
};

class Regionizer {
 public:
  Regionizer(const CameraImage& image, const ScanGrid& grid, const FieldBoundary* boundary)
      : p_{image.yuyv.data(), image.width, image.height}, grid_(grid), boundary_(boundary) {}

  ScanLineRegions run(CameraId camera) {
    ScanLineRegions out;
    out.camera = camera;
    stats_.clear();
    scanVertical(out);
    verticalCount_ = stats_.size();
    scanHorizontal(out);
    uniteSimilar(out);
    findFieldColour(out);
    member_.assign(stats_.size(), 0);
    if (out.fieldColour.valid) {
      classifyField(out.vertical, 0, out.fieldColour);
      classifyField(out.horizontal, verticalCount_, out.fieldColour);
      findWhitePoint(out, out.fieldColour);
      classifyWhite(out.vertical, 0, out.fieldColour);
      classifyWhite(out.horizontal, verticalCount_, out.fieldColour);
      markSaturated(out);
      markWideWhite(out);
      markNearClipped(out);
    } else {
      for (auto* lines : {&out.vertical, &out.horizontal})
        for (ScanLine& line : *lines)
          for (ScanRegion& r : line.regions) r.cls = RegionClass::Other;
    }
    cleanup(out.vertical, true);
    cleanup(out.horizontal, false);
    return out;
  }

 private:
  // The first row of vertical line x that is scanned.
  int verticalStart(int x, int top) const {
    if (!boundary_ || !boundary_->valid) return top;
    return std::max(top, static_cast<int>(std::ceil(boundary_->yAt(x + 0.5) - 0.5)));
  }

  void scanVertical(ScanLineRegions& out) {
    const auto& rows = grid_.sampleRows;
    samples_.clear();
    lineSampleBegin_.clear();
    for (std::size_t i = 0; i < grid_.xs.size(); ++i) {
      const int x = grid_.xs[i];
      const int start = verticalStart(x, grid_.topY[i]), end = grid_.bottomY[i];
      ScanLine line;
      line.coord = x;
      line.start = start;
      line.end = std::max(start, end);
      lineSampleBegin_.push_back(samples_.size());
      if (end - start >= 2) {
        samples_.push_back(sampleVertical(p_, x, start));
        for (auto it = std::upper_bound(rows.begin(), rows.end(), start); it != rows.end() && *it < end; ++it)
          samples_.push_back(sampleVertical(p_, x, *it));
        if (samples_.back().pos < end - 1) samples_.push_back(sampleVertical(p_, x, end - 1));
      }
      out.vertical.push_back(std::move(line));
    }
    lineSampleBegin_.push_back(samples_.size());
    // This image's edge thresholds: multiples of the median difference between neighbouring
    // samples (most neighbours lie in one region, so this is the noise and texture level).
    diffs_.clear();
    chromaDiffs_.clear();
    for (std::size_t i = 0; i + 1 < lineSampleBegin_.size(); ++i)
      for (std::size_t k = lineSampleBegin_[i] + 1, j = lineSampleBegin_[i]; k < lineSampleBegin_[i + 1]; ++k) {
        while (j + 1 < k && samples_[j + 1].pos <= samples_[k].pos - kCompareDistance) ++j;
        const Sample &a = samples_[j], &b = samples_[k];
        diffs_.push_back(std::abs(b.y - a.y));
        chromaDiffs_.push_back(std::abs(b.u - a.u) + std::abs(b.v - a.v));
      }
    edgeT_ = std::max(kMinEdge, kEdgeNoiseFactor * median(diffs_));
    chromaT_ = std::max(kMinChromaEdge, kChromaNoiseFactor * median(chromaDiffs_));
    for (std::size_t i = 0; i < out.vertical.size(); ++i) {
      ScanLine& line = out.vertical[i];
      const float share = static_cast<float>(grid_.minSpacing << grid_.levels[i]);
      makeRegions(line, lineSampleBegin_[i], lineSampleBegin_[i + 1], true, share);
    }
  }

  void scanHorizontal(ScanLineRegions& out) {
    hExtra_.clear();
    for (std::size_t i = 0; i < grid_.ys.size(); ++i) {
      const int y = grid_.ys[i];
      int left = grid_.leftX[i], right = grid_.rightX[i];
      if (boundary_ && boundary_->valid) cutRow(*boundary_, y, left, right);
      if (right - left < 2) continue;
      ScanLine line;
      line.coord = y;
      line.start = left;
      line.end = right;
      const std::size_t begin = samples_.size();
      const int step = grid_.xStep[i];
      for (int x = left; x < right; x += step) samples_.push_back(sampleHorizontal(p_, x, y));
      if (samples_.back().pos < right - 1) samples_.push_back(sampleHorizontal(p_, right - 1, y));
      // Spacing to the neighbouring horizontal lines: the line's share of the image. An extra
      // row (see ScanGrid::extraRow) has none: it adds no weight to the colour statistics.
      const bool extra = i < grid_.extraRow.size() && grid_.extraRow[i];
      const float share = extra ? 0.f : static_cast<float>(std::max(1.0f, grid_.lineWidthPx[y]));
      makeRegions(line, begin, samples_.size(), false, share);
      out.horizontal.push_back(std::move(line));
      hExtra_.push_back(extra);
    }
  }

  // Region edges between samples [b, e) of a line, then the regions' mean colours.
  void makeRegions(ScanLine& line, std::size_t b, std::size_t e, bool vertical, float share) {
    if (e <= b) return;
    cuts_.clear();
    cuts_.push_back(line.start);
    // Each sample is compared with the last one at least kCompareDistance before it (and not
    // before the last edge): closer smoothed samples share pixels and would see only part of
    // a step.
    std::size_t ref = b, j = b;
    for (std::size_t k = b + 1; k < e; ++k) {
      while (j + 1 < k && samples_[j + 1].pos <= samples_[k].pos - kCompareDistance) ++j;
      const std::size_t from = samples_[j].pos <= samples_[k].pos - kCompareDistance && j >= ref ? j : std::max(ref, k - 1);
      const Sample &s0 = samples_[from], &s1 = samples_[k];
      const float dy = s1.y - s0.y;
      const float dc = std::abs(s1.u - s0.u) + std::abs(s1.v - s0.v);
      int at = -1;
      if (std::abs(dy) > edgeT_) {
        const int sign = dy > 0 ? 1 : -1;
        int best = -1 << 30;
        for (int q = s0.pos + 1; q <= s1.pos; ++q) {
          const int d = sign * (vertical ? derivVertical(p_, line.coord, q) : derivHorizontal(p_, q, line.coord));
          if (d > best) best = d, at = q;
        }
      } else if (dc > chromaT_) {
        int best = -1;
        for (int q = s0.pos + 1; q <= s1.pos; ++q) {
          const int d = vertical ? chromaDerivVertical(p_, line.coord, q) : chromaDerivHorizontal(p_, q, line.coord);
          if (d > best) best = d, at = q;
        }
      }
      if (at > cuts_.back()) {
        cuts_.push_back(at);
        ref = k;
      }
    }
    cuts_.push_back(line.end);
    line.regions.reserve(cuts_.size() - 1);
    for (std::size_t r = 0; r + 1 < cuts_.size(); ++r) {
      const int from = cuts_[r], to = cuts_[r + 1];
      if (to <= from) continue;
      // Mean of the region's pixels on the line (at most ~12 of them for long regions).
      const int len = to - from;
      const int stride = std::max(1, len / 12);
      int sy = 0, su = 0, sv = 0, n = 0;
      for (int q = from + stride / 2; q < to; q += stride, ++n) {
        const int x = vertical ? line.coord : q, y = vertical ? q : line.coord;
        sy += p_.Y(x, y);
        su += p_.U(x, y);
        sv += p_.V(x, y);
      }
      const float my = static_cast<float>(sy) / n, mu = static_cast<float>(su) / n, mv = static_cast<float>(sv) / n;
      ScanRegion region;
      region.from = from;
      region.to = to;
      region.colour = toYhs(my, mu, mv);
      region.u = static_cast<std::uint8_t>(std::lround(mu));
      region.v = static_cast<std::uint8_t>(std::lround(mv));
      line.regions.push_back(region);
      const int mid = std::clamp((from + to) / 2, 0, vertical ? grid_.height - 1 : grid_.width - 1);
      const float expected = std::max(1.f, vertical ? grid_.lineHeightPx[mid] : grid_.lineWidthPx[line.coord]);
      stats_.push_back({my, mu, mv, chromaOf(mu, mv), len * share, len / expected});
    }
  }

  // The median of non-negative values, to a quarter unit (a histogram: linear time).
  static float median(const std::vector<float>& v) {
    if (v.empty()) return 0;
    std::array<int, 1024> hist{};
    for (float x : v) ++hist[std::min(1023, static_cast<int>(x * 4))];
    std::size_t acc = 0;
    for (int i = 0; i < 1024; ++i)
      if ((acc += hist[i]) * 2 >= v.size()) return (i + 0.5f) / 4;
    return 256;
  }

  // --- Field colour --------------------------------------------------------------------------

  int find(int a) {
    while (parent_[a] != a) a = parent_[a] = parent_[parent_[a]];
    return a;
  }
  // Unites the sets of two touching regions if the regions and the sets' mean colours are
  // similar (comparing the means too keeps chains of slightly different regions -- a blurred
  // edge from a line into the field -- from bridging different surfaces).
  void tryUnite(int a, int b) {
    const int ra = find(a), rb = find(b);
    if (ra == rb || !similar(stats_[a], stats_[b])) return;
    const SetSum &sa = sets_[ra], &sb = sets_[rb];
    if (!similar(sa.mean(), sb.mean())) return;
    const int root = std::min(ra, rb), other = std::max(ra, rb);
    parent_[other] = root;
    sets_[root].add(sets_[other]);
  }
  bool similar(const RegionStats& a, const RegionStats& b) const {
    const float tY = std::max(kSimilarEdges * static_cast<float>(edgeT_), kSimilarY * std::max(a.y, b.y));
    if (std::abs(a.y - b.y) > tY) return false;
    const float tC = std::max(static_cast<float>(chromaT_) * 0.5f, kSimilarChroma * std::max(a.chroma, b.chroma));
    return std::abs(a.u - b.u) + std::abs(a.v - b.v) <= tC;
  }
  static bool plausibleField(float y, float u, float v) {
    const Yhs c = toYhs(y, u, v);
    const float chroma = chromaOf(u, v);
    return c.h >= kGreenHueMin && c.h <= kGreenHueMax && chroma >= kMinFieldChroma &&
           chroma >= kMinFieldChromaPerY * y;
  }

  // Unites similar regions that touch: overlapping regions of neighbouring vertical lines,
  // of neighbouring horizontal lines, and a vertical and a horizontal region that cross.
  void uniteSimilar(const ScanLineRegions& out) {
    const int n = static_cast<int>(stats_.size());
    parent_.resize(n);
    std::iota(parent_.begin(), parent_.end(), 0);
    sets_.resize(n);
    for (int r = 0; r < n; ++r) {
      const RegionStats& st = stats_[r];
      sets_[r] = {st.area, st.area * st.y, st.area * st.u, st.area * st.v};
    }
    std::vector<int> vOffset(out.vertical.size() + 1, 0), hOffset(out.horizontal.size() + 1, 0);
    for (std::size_t i = 0; i < out.vertical.size(); ++i)
      vOffset[i + 1] = vOffset[i] + static_cast<int>(out.vertical[i].regions.size());
    hOffset[0] = static_cast<int>(verticalCount_);
    for (std::size_t i = 0; i < out.horizontal.size(); ++i)
      hOffset[i + 1] = hOffset[i] + static_cast<int>(out.horizontal[i].regions.size());
    // Regions of lines a and b overlapping within [lo, hi) along the lines.
    auto uniteOverlapping = [&](const ScanLine& a, int offA, const ScanLine& b, int offB, int lo, int hi) {
      std::size_t ra = 0, rb = 0;
      while (ra < a.regions.size() && a.regions[ra].to <= lo) ++ra;
      while (rb < b.regions.size() && b.regions[rb].to <= lo) ++rb;
      while (ra < a.regions.size() && rb < b.regions.size() && a.regions[ra].from < hi && b.regions[rb].from < hi) {
        const int ga = offA + static_cast<int>(ra), gb = offB + static_cast<int>(rb);
        tryUnite(ga, gb);
        if (a.regions[ra].to < b.regions[rb].to) ++ra;
        else ++rb;
      }
    };
    // Vertical lines with their right neighbours: the next line, and where that one ends (a
    // finer level), the next one reaching further down.
    for (std::size_t i = 0; i < out.vertical.size(); ++i) {
      const ScanLine& a = out.vertical[i];
      int covered = a.start;
      for (std::size_t j = i + 1; j < out.vertical.size() && covered < a.end; ++j) {
        const ScanLine& b = out.vertical[j];
        if (grid_.xs[j] - grid_.xs[i] > (grid_.minSpacing << (grid_.levels[i] + 1))) break;
        const int lo = std::max(covered, b.start), hi = std::min(a.end, b.end);
        if (hi <= lo) continue;
        uniteOverlapping(a, vOffset[i], b, vOffset[j], lo, hi);
        covered = std::max(covered, hi);
      }
    }
    // (Extra rows take no part: the field colour comes from the regular lines alone.)
    for (std::size_t i = 0, j = 0; i < out.horizontal.size(); i = j) {
      for (j = i + 1; j < out.horizontal.size() && hExtra_[j]; ++j) {
      }
      if (j >= out.horizontal.size() || hExtra_[i]) continue;
      const ScanLine &a = out.horizontal[i], &b = out.horizontal[j];
      uniteOverlapping(a, hOffset[i], b, hOffset[j], std::max(a.start, b.start), std::min(a.end, b.end));
    }
    // Crossings: walk each vertical line's regions down the horizontal lines (both sorted),
    // each horizontal line's regions along the vertical lines (ascending x).
    std::vector<std::size_t> rh(out.horizontal.size(), 0);
    for (std::size_t v = 0; v < out.vertical.size(); ++v) {
      const ScanLine& vl = out.vertical[v];
      const int x = vl.coord;
      std::size_t rv = 0;
      for (std::size_t h = 0; h < out.horizontal.size(); ++h) {
        const ScanLine& hl = out.horizontal[h];
        const int y = hl.coord;
        if (hExtra_[h] || y < vl.start) continue;
        if (y >= vl.end) break;
        if (x < hl.start || x >= hl.end) continue;
        while (rv < vl.regions.size() && vl.regions[rv].to <= y) ++rv;
        while (rh[h] < hl.regions.size() && hl.regions[rh[h]].to <= x) ++rh[h];
        if (rv >= vl.regions.size() || rh[h] >= hl.regions.size()) continue;
        tryUnite(vOffset[v] + static_cast<int>(rv), hOffset[h] + static_cast<int>(rh[h]));
      }
    }
  }

  void findFieldColour(ScanLineRegions& out) {
    FieldColour& fc = out.fieldColour;
    fc.edgeThreshold = edgeT_;
    const int n = static_cast<int>(stats_.size());
    // The united regions' areas and mean colours.
    std::vector<double> area(n, 0), sy(n, 0), su(n, 0), sv(n, 0), st(n, 0);
    double total = 0, meanY = 0, meanS = 0;
    for (int r = 0; r < n; ++r) {
      const RegionStats& s = stats_[r];
      const int root = find(r);
      area[root] += s.area;
      sy[root] += s.area * s.y;
      su[root] += s.area * s.u;
      sv[root] += s.area * s.v;
      st[root] += s.area * s.thick;
      total += s.area;
      meanY += s.area * s.y;
      meanS += s.area * std::min(255.f, 2 * s.chroma);
    }
    if (total <= 0) return;
    fc.meanY = meanY / total;
    fc.meanS = meanS / total;
    isFieldSet_.assign(n, 0);
    // The dominant plausible set, then every big plausible set that is not "whiter" than it
    // (a long field line across the image also unites into a big set, but it is brighter and
    // much less saturated for its luminance than the field).
    auto setY = [&](int r) { return sy[r] / area[r]; };
    auto setRatio = [&](int r) { return chromaOf(su[r] / area[r], sv[r] / area[r]) / std::max(1.0, setY(r)); };
    int dominant = -1;
    for (int r = 0; r < n; ++r) {
      if (find(r) != r || area[r] <= 0) continue;
      if (!plausibleField(sy[r] / area[r], su[r] / area[r], sv[r] / area[r])) continue;
      if (dominant < 0 || area[r] > area[dominant]) dominant = r;
    }
    if (dominant < 0 || area[dominant] < kMinSetFraction * total) return;
    isFieldSet_[dominant] = 1;
    for (int r = 0; r < n; ++r) {
      if (find(r) != r || r == dominant || area[r] < kBigSetFraction * total) continue;
      if (!plausibleField(sy[r] / area[r], su[r] / area[r], sv[r] / area[r])) continue;
      // Brighter and greyer for its luminance than the dominant set, thin like a line, and
      // without more chroma: lines. (The same green in the sun is greyer for its luminance
      // too, since the camera compresses bright colours, but it is a surface, not thin, or
      // its chroma grows with the light.)
      if (setY(r) > kWhiterY * setY(dominant) + edgeT_ && setRatio(r) < kWhiterRatio * setRatio(dominant) &&
          st[r] / area[r] < kThinSet && setRatio(r) * setY(r) < kWhiterChroma * setRatio(dominant) * setY(dominant))
        continue;
      isFieldSet_[r] = 1;
    }
    // The field colour range: percentiles over the regions of the field sets.
    double fy = 0, fu = 0, fv = 0, fa = 0;
    for (int r = 0; r < n; ++r)
      if (isFieldSet_[find(r)]) {
        const RegionStats& s = stats_[r];
        fy += s.area * s.y, fu += s.area * s.u, fv += s.area * s.v, fa += s.area;
      }
    const Yhs mean = toYhs(fy / fa, fu / fa, fv / fa);
    fieldMean_ = {static_cast<float>(fy / fa), static_cast<float>(fu / fa), static_cast<float>(fv / fa),
                  chromaOf(fu / fa, fv / fa), static_cast<float>(fa), 0};
    std::array<double, 256> hHist{}, sHist{}, yHist{}, rHist{};  // rHist: chroma / luminance in 1/128
    for (int r = 0; r < n; ++r)
      if (isFieldSet_[find(r)]) {
        const RegionStats& s = stats_[r];
        const Yhs c = toYhs(s.y, s.u, s.v);
        hHist[hueOffset(mean.h, c.h) + 128] += s.area;
        sHist[c.s] += s.area;
        yHist[c.y] += s.area;
        rHist[std::min(255, static_cast<int>(128 * s.chroma / std::max(1.f, s.y)))] += s.area;
      }
    auto percentile = [&](const std::array<double, 256>& h, double q) {
      double acc = 0;
      for (int i = 0; i < 256; ++i)
        if ((acc += h[i]) >= q * fa) return i;
      return 255;
    };
    const int hLo = percentile(hHist, 0.01) - 128, hHi = percentile(hHist, 0.99) - 128;
    fc.valid = true;
    fc.hueMin = static_cast<std::uint8_t>((mean.h + hLo - kHueMargin) & 255);
    fc.hueMax = static_cast<std::uint8_t>((mean.h + hHi + kHueMargin) & 255);
    fc.satMin = static_cast<std::uint8_t>(std::clamp(0.7 * percentile(sHist, 0.02), 2 * kMinFieldChroma, 255.0));
    fc.yMin = static_cast<std::uint8_t>(std::clamp(0.6 * percentile(yHist, 0.01), 0.0, 255.0));
    fc.yMax = static_cast<std::uint8_t>(std::clamp(percentile(yHist, 0.99) + edgeT_, 0.0, 255.0));
    fc.fieldY = static_cast<std::uint8_t>(percentile(yHist, 0.5));
    fc.fieldS = static_cast<std::uint8_t>(percentile(sHist, 0.5));
    fc.fieldHue = mean.h;
    ratioMin_ = 0.7 * percentile(rHist, 0.02) / 128.0;
    fieldRatio_ = percentile(rHist, 0.5) / 128.0;
    // White: clearly brighter than the field (and not darker than most of the image), and
    // less saturated for its luminance than the field.
    const double whiteY = std::max(fc.fieldY + std::max(2 * edgeT_, kWhiteGain * fc.fieldY), 0.9 * fc.meanY);
    fc.whiteYMin = static_cast<std::uint8_t>(std::clamp(whiteY, 0.0, 255.0));
  }

  bool inFieldRange(const FieldColour& fc, const Yhs& c, const RegionStats& s) const {
    if (!fc.valid) return false;
    if (c.s < fc.satMin || c.y < fc.yMin || c.y > fc.yMax) return false;
    if (s.chroma < ratioMin_ * s.y) return false;
    return hueOffset(fc.hueMin, c.h) >= 0 && hueOffset(fc.hueMin, c.h) <= hueOffset(fc.hueMin, fc.hueMax);
  }
  // The field's hue with at least half the field's chroma for its luminance.
  bool paleField(const FieldColour& fc, const Yhs& c, const RegionStats& s) const {
    return s.chroma >= kMinFieldChroma && s.chroma >= kPaleRatio * fieldRatio_ * s.y &&
           hueOffset(fc.hueMin, c.h) >= 0 && hueOffset(fc.hueMin, c.h) <= hueOffset(fc.hueMin, fc.hueMax);
  }
  // Chroma relative to this image's white point (what a white surface looks like under this
  // light: without white balance, warm light makes lines orange).
  float whiteChroma(const RegionStats& s) const {
    const float du = s.u - 128 - s.y * whiteU_, dv = s.v - 128 - s.y * whiteV_;
    return std::sqrt(du * du + dv * dv);
  }
  float whiteRatio(const RegionStats& s) const { return whiteChroma(s) / std::max(1.f, s.y); }
  bool whiteGlobal(const FieldColour& fc, const RegionStats& s) const {
    return s.y >= fc.whiteYMin && whiteRatio(s) <= fc.whiteChromaPerY;
  }
  // Clearly brighter than the field beside it (a line in a shadow stripe may be darker than
  // the sunlit field elsewhere).
  bool brighterThan(const RegionStats& s, const RegionStats& field) const {
    return s.y >= field.y + std::max(kLocalWhiteEdges * static_cast<float>(edgeT_), kLocalWhiteGain * field.y);
  }
  // ... and less saturated for its luminance than it.
  bool whiteLocal(const RegionStats& s, const RegionStats& field) const {
    return brighterThan(s, field) && whiteRatio(s) <= kLocalWhiteRatio * whiteRatio(field);
  }

  // Field: members of the field sets, and regions in the field colour range.
  void classifyField(std::vector<ScanLine>& lines, std::size_t g, const FieldColour& fc) {
    for (ScanLine& line : lines)
      for (ScanRegion& r : line.regions) {
        member_[g] = fc.valid && isFieldSet_[find(static_cast<int>(g))];
        r.cls = member_[g] || inFieldRange(fc, r.colour, stats_[g]) ? RegionClass::Field : RegionClass::Other;
        ++g;
      }
  }

  // Regions standing out brightly from the field on both sides (lines, mostly, and robots
  // and balls, all white or grey in the SPL): their median chroma per luminance is the
  // image's white point.
  void findWhitePoint(const ScanLineRegions& out, FieldColour& fc) {
    whiteU_ = whiteV_ = 0;
    std::vector<std::pair<float, float>> us, vs;  // (value, weight)
    double total = 0;
    auto collect = [&](const std::vector<ScanLine>& lines, std::size_t g, const std::vector<char>* extra) {
      for (std::size_t l = 0; l < lines.size(); ++l) {
        const ScanLine& line = lines[l];
        if (extra && (*extra)[l]) {
          g += line.regions.size();
          continue;
        }
        for (std::size_t k = 1; k + 1 < line.regions.size(); ++k) {
          const std::size_t i = g + k;
          if (member_[i] || line.regions[k - 1].cls != RegionClass::Field || line.regions[k + 1].cls != RegionClass::Field)
            continue;
          const RegionStats& s = stats_[i];
          if (!brighterThan(s, stats_[i - 1]) || !brighterThan(s, stats_[i + 1])) continue;
          const float w = static_cast<float>(line.regions[k].to - line.regions[k].from);
          us.emplace_back((s.u - 128) / std::max(1.f, s.y), w);
          vs.emplace_back((s.v - 128) / std::max(1.f, s.y), w);
          total += w;
        }
        g += line.regions.size();
      }
    };
    collect(out.vertical, 0, nullptr);
    collect(out.horizontal, verticalCount_, &hExtra_);
    if (!us.empty()) estimateWhitePoint(us, vs, total);
    fc.whiteU = whiteU_;
    fc.whiteV = whiteV_;
    // The global white threshold on chroma, relative to the field's (both about the white point).
    fc.whiteChromaPerY = kWhiteRatio * whiteRatio(fieldMean_);
    fc.whiteSMax = static_cast<std::uint8_t>(std::clamp(2 * fc.whiteChromaPerY * fc.whiteYMin, 0.0, 255.0));
  }

  void estimateWhitePoint(std::vector<std::pair<float, float>>& us, std::vector<std::pair<float, float>>& vs,
                          double total) {
    auto weightedMedian = [&](std::vector<std::pair<float, float>>& v) {
      std::sort(v.begin(), v.end());
      double acc = 0;
      for (const auto& [value, w] : v)
        if ((acc += w) * 2 >= total) return value;
      return v.back().first;
    };
    whiteU_ = weightedMedian(us);
    whiteV_ = weightedMedian(vs);
    // Only the part across the field's own chroma direction: a light's cast moves white
    // along the orange-blue axis, about square to green, while pale field patches among the
    // candidates would pull it towards green.
    const float du = fieldMean_.u - 128, dv = fieldMean_.v - 128, dn = std::sqrt(du * du + dv * dv);
    if (dn > 1e-3f) {
      const float along = (whiteU_ * du + whiteV_ * dv) / dn;
      whiteU_ -= along * du / dn;
      whiteV_ -= along * dv / dn;
    }
    const float norm = std::sqrt(whiteU_ * whiteU_ + whiteV_ * whiteV_);
    if (norm > kMaxWhitePoint) whiteU_ *= kMaxWhitePoint / norm, whiteV_ *= kMaxWhitePoint / norm;
  }

  void classifyWhite(std::vector<ScanLine>& lines, std::size_t g, const FieldColour& fc) {
    if (!fc.valid) return;
    for (ScanLine& line : lines) {
      const std::size_t first = g;
      g += line.regions.size();
      for (std::size_t k = 0; k < line.regions.size(); ++k) {
        ScanRegion& r = line.regions[k];
        const RegionStats& s = stats_[first + k];
        if (member_[first + k]) continue;
        // In the field range: white only if it stands out from the field beside it.
        bool white = r.cls != RegionClass::Field && whiteGlobal(fc, s);
        if (!white) {
          const bool fieldBefore = k > 0 && line.regions[k - 1].cls == RegionClass::Field;
          const bool fieldAfter = k + 1 < line.regions.size() && line.regions[k + 1].cls == RegionClass::Field;
          if (fieldBefore || fieldAfter)
            white = (!fieldBefore || whiteLocal(s, stats_[first + k - 1])) &&
                    (!fieldAfter || whiteLocal(s, stats_[first + k + 1]));
        }
        // Much longer than a line is thick, in a plausible field colour: a pale (sunlit,
        // washed-out) part of the field, not a line.
        if (s.thick > kThickWhite && paleField(fc, r.colour, s)) r.cls = RegionClass::Field;
        else if (white) r.cls = RegionClass::White;
      }
    }
  }

  // --- Wide white (ScanLineRegionizer.h, step 3c) ---------------------------------------------
  // A line is thin across itself. A white stretch (consecutive white regions) of t line sizes
  // along its scan line, crossed by white w line widths across it, is about 1 / sqrt(1 / t^2 +
  // 1 / w^2) line widths wide on the ground: 1 for a line at any angle (a line running up the
  // image is long on a vertical scan line and one line width across it). Wider than kWide (10
  // cm), it is no paint but a surface; in the field's hue about the white point, it is the
  // sunlit carpet between shadow stripes, washed out to a bright grey: field. On a vertical
  // line the width is that of the long white (or Unknown) on the neighbouring vertical lines,
  // at a quarter, half and three quarters of the stretch, and two of the three must be wide (a
  // junction of two lines is wide at one). On a horizontal line the crossing white is that of
  // the vertical lines at those three columns (or their stretch was found a surface). A ball is
  // at most two line widths across. A robot stands up from the field: on a vertical line its
  // white has no field above it (and its grey is rarely in the field's hue about the white
  // point, though warm light can put it there), so a vertical stretch needs field or Unknown
  // on both sides, and a vertical stretch counts across a horizontal one only with the field
  // beyond it. Sizes allow kLineBlurPx of blur.
  bool fieldHueAboutWhite(const FieldColour& fc, const RegionStats& s) const {
    const float du = s.u - 128 - s.y * whiteU_, dv = s.v - 128 - s.y * whiteV_;
    if (std::sqrt(du * du + dv * dv) < kMinFieldChroma) return false;
    const Yhs c = toYhs(s.y, 128 + du, 128 + dv);
    return hueOffset(fc.hueMin, c.h) >= 0 && hueOffset(fc.hueMin, c.h) <= hueOffset(fc.hueMin, fc.hueMax);
  }

  void markWideWhite(ScanLineRegions& out) {
    indexLines(out);
    const auto passable = [](RegionClass c) { return c == RegionClass::Field || c == RegionClass::Unknown; };
    const auto along = [&](int from, int to) {
      const int mid = std::clamp((from + to) / 2, 0, grid_.height - 1);
      return (to - from) / (grid_.lineHeightPx[mid] + kLineBlurPx);
    };
    // Per region of a vertical line: its white stretch's length in line heights, and whether
    // the field (or Unknown) lies beyond it (above it in the image).
    std::vector<float> tV(verticalCount_, 0);
    std::vector<char> fieldBeyond(verticalCount_, 0);
    for (std::size_t v = 0; v < out.vertical.size(); ++v) {
      const auto& rs = out.vertical[v].regions;
      for (std::size_t k0 = 0; k0 < rs.size();) {
        std::size_t k1 = k0 + 1;
        if (rs[k0].cls == RegionClass::White) {
          while (k1 < rs.size() && rs[k1].cls == RegionClass::White) ++k1;
          std::fill(tV.begin() + firstV_[v] + k0, tV.begin() + firstV_[v] + k1, along(rs[k0].from, rs[k1 - 1].to));
          if (k0 > 0 && passable(rs[k0 - 1].cls))
            std::fill(fieldBeyond.begin() + firstV_[v] + k0, fieldBeyond.begin() + firstV_[v] + k1, 1);
        }
        k0 = k1;
      }
    }
    // At row y, vertical line v: -1 if it does not reach y, else whether it is in a long white
    // stretch (or Unknown) there.
    const auto whiteAt = [&](std::size_t v, int y) {
      const long g = regionAt(out.vertical[v], firstV_[v], y);
      if (g < 0) return -1;
      const RegionClass c = out.vertical[v].regions[g - firstV_[v]].cls;
      return c == RegionClass::Unknown || (c == RegionClass::White && tV[g] > kWideLong) ? 1 : 0;
    };
    // The white's width at row y about vertical line v: from the outermost vertical lines on
    // either side that are still white there (lines that do not reach the row are passed over).
    const auto widthAt = [&](std::size_t v, int y) {
      std::size_t lo = v, hi = v;
      for (std::size_t j = v; j-- > 0;) {
        const int w = whiteAt(j, y);
        if (w == 0) break;
        if (w == 1) lo = j;
      }
      for (std::size_t j = v + 1; j < out.vertical.size(); ++j) {
        const int w = whiteAt(j, y);
        if (w == 0) break;
        if (w == 1) hi = j;
      }
      return static_cast<float>(out.vertical[hi].coord - out.vertical[lo].coord);
    };
    std::vector<char> surface(stats_.size(), 0);
    // Maximal stretches [k0, k1) of white regions in the field's hue (about the white point)
    // lying on the field: on a vertical line with field or Unknown above and below (a robot or a
    // person stands up from the field: above its white is no field), on a horizontal line on at
    // least one side (a foot may stand on the other). The image border counts as field, the
    // top of a vertical line (the field ends there) and a line's end inside the image do not.
    // Below the end of a vertical line that ends inside the image (the grid's coarser lines
    // carry on there): what the nearest line carrying on shows there, past its white.
    const auto fieldBelow = [&](std::size_t v) {
      const int y = out.vertical[v].end;
      for (std::size_t d = 1; d < out.vertical.size(); ++d)
        for (const std::size_t j : {v - d, v + d}) {
          if (j >= out.vertical.size()) continue;  // (wrapped below zero as well)
          const long g = regionAt(out.vertical[j], firstV_[j], y);
          if (g < 0) continue;
          const auto& rs = out.vertical[j].regions;
          std::size_t k = static_cast<std::size_t>(g) - firstV_[j];
          while (k < rs.size() && rs[k].cls == RegionClass::White) ++k;
          return k == rs.size() ? out.vertical[j].end >= grid_.height : passable(rs[k].cls);
        }
      return false;
    };
    const auto stretches = [&](const ScanLine& line, std::size_t first, bool vertical, auto&& visit) {
      const auto& rs = line.regions;
      const bool startOpen = !vertical && line.start == 0;
      const auto endOpen = [&] {
        return line.end >= (vertical ? grid_.height : grid_.width) ||
               (vertical && fieldBelow(static_cast<std::size_t>(&line - out.vertical.data())));
      };
      for (std::size_t k0 = 0; k0 < rs.size();) {
        if (rs[k0].cls != RegionClass::White) {
          ++k0;
          continue;
        }
        std::size_t k1 = k0;
        while (k1 < rs.size() && rs[k1].cls == RegionClass::White) ++k1;
        const bool before = k0 == 0 ? startOpen : passable(rs[k0 - 1].cls);
        const auto after = [&] { return k1 == rs.size() ? endOpen() : passable(rs[k1].cls); };
        if (vertical ? before && after() : before || after()) {
          SetSum sum;
          for (std::size_t k = k0; k < k1; ++k) {
            const RegionStats& st = stats_[first + k];
            const double len = rs[k].to - rs[k].from;
            sum.add({len, len * st.y, len * st.u, len * st.v});
          }
          if (fieldHueAboutWhite(out.fieldColour, sum.mean())) visit(k0, k1, rs[k0].from, rs[k1 - 1].to);
        }
        k0 = k1;
      }
    };
    for (std::size_t v = 0; v < out.vertical.size(); ++v)
      stretches(out.vertical[v], firstV_[v], true, [&](std::size_t k0, std::size_t k1, int from, int to) {
        const float t = along(from, to);
        if (t <= kWideLong) return;
        int wideRows = 0;
        for (int q = 1; q <= 3; ++q) {
          const int y = from + q * (to - from) / 4;
          const float w = widthAt(v, y) / (grid_.lineWidthPx[y] + kLineBlurPx);
          wideRows += w > 0 && 1 / std::sqrt(1 / (t * t) + 1 / (w * w)) > kWide;
        }
        const bool wide = wideRows >= 2;
        if (wide) std::fill(surface.begin() + firstV_[v] + k0, surface.begin() + firstV_[v] + k1, 1);
      });
    // On a horizontal line: at column x, the vertical line nearest it (of those reaching row y)
    // found a surface there, or is in white with the field beyond it that makes the white at
    // least kWide line widths wide together with the horizontal stretch (tH line widths long).
    // (A robot's leg has the robot above it, not the field.)
    const auto wideAcross = [&](int x, int y, float tH) {
      const auto it = std::lower_bound(out.vertical.begin(), out.vertical.end(), x,
                                       [](const ScanLine& l, int q) { return l.coord < q; });
      // The nearest vertical line on either side that reaches row y.
      long g = -1;
      int best = 1 << 30;
      for (std::size_t j = static_cast<std::size_t>(it - out.vertical.begin()); j < out.vertical.size(); ++j) {
        const long r = regionAt(out.vertical[j], firstV_[j], y);
        if (r < 0) continue;
        if (out.vertical[j].coord - x < best) best = out.vertical[j].coord - x, g = r;
        break;
      }
      for (std::size_t j = static_cast<std::size_t>(it - out.vertical.begin()); j-- > 0;) {
        const long r = regionAt(out.vertical[j], firstV_[j], y);
        if (r < 0) continue;
        if (x - out.vertical[j].coord < best) best = x - out.vertical[j].coord, g = r;
        break;
      }
      if (g < 0) return false;
      if (surface[g]) return true;
      const float t = tV[g];
      return fieldBeyond[g] && t > 0 && 1 / std::sqrt(1 / (t * t) + 1 / (tH * tH)) > kWide;
    };
    for (std::size_t h = 0; h < out.horizontal.size(); ++h) {
      const int y = out.horizontal[h].coord;
      stretches(out.horizontal[h], firstH_[h], false, [&](std::size_t k0, std::size_t k1, int from, int to) {
        const float tH = (to - from) / (grid_.lineWidthPx[y] + kLineBlurPx);
        if (tH <= kWideLong) return;
        int wideCols = 0;
        for (int q = 1; q <= 3; ++q) wideCols += wideAcross(from + q * (to - from) / 4, y, tH);
        if (wideCols >= 2) std::fill(surface.begin() + firstH_[h] + k0, surface.begin() + firstH_[h] + k1, 1);
      });
    }
    setClass(out, surface, RegionClass::Field);
  }

  // --- Near the clipping level (ScanLineRegionizer.h, step 3d) -------------------------------
  // Where a region's brightest channel is at or just below this image's clipping level, the
  // sensor has cut that channel and the others catch up: what is left of its chroma is a lower
  // bound, not a measurement. A sunlit carpet whose green clips keeps a trace of the field's hue
  // and looks white by colour; a line at the clipping level is R = G = B, without hue. So white
  // there, more than two line sizes thick, in the field's hue about the white point, is Unknown:
  // neither white nor field, no line spot and no field colour comes from it.
  void markNearClipped(ScanLineRegions& out) {
    if (out.saturationLevel < 0) return;
    const float clip = static_cast<float>(out.saturationLevel);
    std::vector<char> flagged(stats_.size(), 0);
    std::size_t g = 0;
    for (auto* lines : {&out.vertical, &out.horizontal})
      for (ScanLine& line : *lines)
        for (ScanRegion& r : line.regions) {
          const RegionStats& s = stats_[g];
          // The brightest channel (RGB is linear in YUV: that of the region's mean colour).
          const float du = s.u - 128, dv = s.v - 128;
          const float top = std::max({s.y + 1.402f * dv, s.y - 0.344f * du - 0.714f * dv, s.y + 1.772f * du});
          flagged[g++] = r.cls == RegionClass::White && s.thick > kSaturatedLineThick &&
                         top >= (1 - kNearClip) * clip && top <= clip + 3 * kSaturatedTolerance &&
                         fieldHueAboutWhite(out.fieldColour, s);
        }
    setClass(out, flagged, RegionClass::Unknown);
  }

  // --- Sensor saturation (ScanLineRegionizer.h, step 3b) -------------------------------------
  // Clipped areas carry no colour: a sunlit carpet, a window, a robot's chest in glare look
  // alike there. They are left Unknown -- neither field nor white -- so that no line spot and
  // no field colour comes from them.
  void markSaturated(ScanLineRegions& out) {
    double total = 0;
    const float clip = saturationLevel(out, total);
    if (clip < 0) return;
    out.saturationLevel = static_cast<int>(std::lround(clip));
    indexLines(out);
    std::vector<char> unknown = saturatedCores(out, clip, total);
    spreadOverEdges(out, unknown);
    setClass(out, unknown, RegionClass::Unknown);
    markExtraRows(out, clip);
    mergeBlurIntoUnknown(out);
  }

  // (Nearly) colourless at the clipping level. Nearly: a long stretch's mean comes from a
  // dozen samples, some of them in the blurred edges of small shadows it runs through.
  static bool nearlySaturated(const RegionStats& s, float clip) {
    return s.chroma < 2 * kSaturatedChroma && std::abs(s.y - clip) <= 3 * kSaturatedTolerance;
  }
  static bool longSaturated(const RegionStats& s, float clip) { return nearlySaturated(s, clip) && s.thick > kThickWhite; }

  // THIS image's clipping level: the luminance at which colourless regions pile up (3 % of the
  // scanned area or more within +-1, four times the area just beside it); -1 if none. total:
  // the scanned area (extra rows left out, as in the colour statistics).
  float saturationLevel(const ScanLineRegions& out, double& total) const {
    std::array<double, 256> hist{};
    total = 0;
    std::size_t g = 0;
    for (const auto* lines : {&out.vertical, &out.horizontal})
      for (std::size_t l = 0; l < lines->size(); ++l) {
        const bool extra = lines == &out.horizontal && hExtra_[l];
        for (std::size_t k = 0; k < (*lines)[l].regions.size(); ++k, ++g) {
          if (extra) continue;
          const RegionStats& s = stats_[g];
          total += s.area;
          if (s.chroma < kSaturatedChroma) hist[std::clamp(static_cast<int>(std::lround(s.y)), 0, 255)] += s.area;
        }
      }
    if (total <= 0) return -1;
    const auto band = [&](int from, int to) {
      double a = 0;
      for (int v = std::max(0, from); v <= std::min(255, to); ++v) a += hist[v];
      return a;
    };
    int level = -1;
    double peak = 0;
    for (int v = kSaturatedMinY; v < 256; ++v)
      if (band(v - 1, v + 1) > peak) peak = band(v - 1, v + 1), level = v;
    if (level < 0 || peak < kSaturatedShare * total) return -1;
    if (peak < kSaturatedSpike * (band(level - 8, level - 2) + band(level + 2, level + 8))) return -1;
    double sum = 0;
    for (int v = level - 1; v <= std::min(255, level + 1); ++v) sum += v * hist[v];
    return static_cast<float>(sum / peak);
  }

  // Gives every region flagged (per region, in stats_ order) the class cls.
  static void setClass(ScanLineRegions& out, const std::vector<char>& flagged, RegionClass cls) {
    std::size_t g = 0;
    for (auto* lines : {&out.vertical, &out.horizontal})
      for (ScanLine& line : *lines)
        for (ScanRegion& r : line.regions)
          if (flagged[g++]) r.cls = cls;
  }

  // Where each line's regions start in stats_.
  void indexLines(const ScanLineRegions& out) {
    firstV_.assign(out.vertical.size(), 0);
    firstH_.assign(out.horizontal.size(), 0);
    for (std::size_t l = 0, g = 0; l < out.vertical.size(); g += out.vertical[l++].regions.size()) firstV_[l] = g;
    for (std::size_t l = 0, g = verticalCount_; l < out.horizontal.size(); g += out.horizontal[l++].regions.size())
      firstH_[l] = g;
  }

  // The index (into stats_) of the region of a line that covers position q, or -1.
  static long regionAt(const ScanLine& line, std::size_t first, int q) {
    const auto& rs = line.regions;
    auto it = std::upper_bound(rs.begin(), rs.end(), q, [](int v, const ScanRegion& r) { return v < r.from; });
    if (it == rs.begin()) return -1;
    --it;
    return q < it->to ? static_cast<long>(first + (it - rs.begin())) : -1;
  }

  // Per region: a core of a saturated surface. A core is a long saturated stretch crossed by
  // at least kSaturatedCrossings long saturated stretches of the other scan direction -- an
  // area clipped in 2-D, not a clipped line (a line seen lengthwise is long one way only; two
  // lines meeting in an L cross once). Cores count only in a saturated surface: a big united
  // set with many crossings (about its clipped area in units of a line's width x a line's
  // height: a few where two lines meet, dozens for a sunlit stripe) and a colourless mean at
  // the level.
  std::vector<char> saturatedCores(const ScanLineRegions& out, float clip, double total) {
    std::vector<std::uint16_t> crossings(stats_.size(), 0);
    for (std::size_t h = 0; h < out.horizontal.size(); ++h) {
      if (hExtra_[h]) continue;
      for (std::size_t v = 0; v < out.vertical.size(); ++v) {
        const long a = regionAt(out.vertical[v], firstV_[v], out.horizontal[h].coord);
        const long b = regionAt(out.horizontal[h], firstH_[h], out.vertical[v].coord);
        if (a < 0 || b < 0 || !longSaturated(stats_[a], clip) || !longSaturated(stats_[b], clip)) continue;
        ++crossings[a], ++crossings[b];
      }
    }
    std::vector<double> coreArea(stats_.size(), 0);
    std::vector<int> setCrossings(stats_.size(), 0);
    std::vector<char> core(stats_.size(), 0);
    for (std::size_t i = 0; i < stats_.size(); ++i) {
      if (crossings[i] < kSaturatedCrossings) continue;
      core[i] = 1;
      const int root = find(static_cast<int>(i));
      coreArea[root] += stats_[i].area;
      if (i < verticalCount_) setCrossings[root] += crossings[i];  // each crossing once
    }
    for (std::size_t i = 0; i < stats_.size(); ++i) {
      const std::size_t root = static_cast<std::size_t>(find(static_cast<int>(i)));
      core[i] = core[i] && coreArea[root] >= kBigSetFraction * total && setCrossings[root] >= kSurfaceCrossings &&
                nearlySaturated(sets_[root].mean(), clip);
    }
    return core;
  }

  // From the cores, kSaturatedReach steps along a line and across to the neighbouring lines of
  // the same direction (overlapping regions): the surface's partly clipped, blurred edges.
  // Field and other regions stop it, and so does what is line-sized between field on both
  // sides. Not the whole united set: a clipped line or goal post is united with a clipped
  // surface it touches somewhere, and would be lost all along.
  void spreadOverEdges(const ScanLineRegions& out, std::vector<char>& reached) const {
    const auto canReach = [&](std::size_t g, const ScanLine& line, std::size_t k) {
      const ScanRegion& r = line.regions[k];
      if (reached[g] || r.cls == RegionClass::Field || r.cls == RegionClass::Other) return false;
      const bool between = k > 0 && k + 1 < line.regions.size() && line.regions[k - 1].cls == RegionClass::Field &&
                           line.regions[k + 1].cls == RegionClass::Field;
      return !(between && stats_[g].thick < kSaturatedLineThick);
    };
    for (int step = 0; step < kSaturatedReach; ++step) {
      std::vector<char> next(reached);
      const auto spread = [&](const std::vector<ScanLine>& lines, const std::vector<std::size_t>& first, bool rows) {
        for (std::size_t l = 0; l < lines.size(); ++l) {
          const ScanLine& a = lines[l];
          for (std::size_t i = 0; i + 1 < a.regions.size(); ++i) {  // along the line
            const std::size_t g = first[l] + i;
            if (reached[g] && canReach(g + 1, a, i + 1)) next[g + 1] = 1;
            if (reached[g + 1] && canReach(g, a, i)) next[g] = 1;
          }
          if (l + 1 >= lines.size() || (rows && (hExtra_[l] || hExtra_[l + 1]))) continue;
          const ScanLine& b = lines[l + 1];  // across to the next line
          for (std::size_t i = 0, k = 0; i < a.regions.size() && k < b.regions.size();) {
            const std::size_t ga = first[l] + i, gb = first[l + 1] + k;
            if (reached[ga] && canReach(gb, b, k)) next[gb] = 1;
            if (reached[gb] && canReach(ga, a, i)) next[ga] = 1;
            if (a.regions[i].to < b.regions[k].to) ++i;
            else ++k;
          }
        }
      };
      spread(out.vertical, firstV_, false);
      spread(out.horizontal, firstH_, true);
      reached.swap(next);
    }
  }

  // The extra rows are in no united set and cross nothing counted: a long saturated stretch
  // on one is Unknown where a vertical line through its middle half says so.
  void markExtraRows(ScanLineRegions& out, float clip) const {
    for (std::size_t h = 0; h < out.horizontal.size(); ++h) {
      if (!hExtra_[h]) continue;
      ScanLine& row = out.horizontal[h];
      for (std::size_t k = 0; k < row.regions.size(); ++k) {
        ScanRegion& r = row.regions[k];
        if (!longSaturated(stats_[firstH_[h] + k], clip)) continue;
        const int mid = (r.from + r.to) / 2;
        for (std::size_t v = 0; v < out.vertical.size() && r.cls != RegionClass::Unknown; ++v) {
          const ScanLine& line = out.vertical[v];
          if (std::abs(line.coord - mid) > (r.to - r.from) / 4) continue;
          const long a = regionAt(line, firstV_[v], row.coord);
          if (a >= 0 && line.regions[a - firstV_[v]].cls == RegionClass::Unknown) r.cls = RegionClass::Unknown;
        }
      }
    }
  }

  // The blur between a saturated stretch and the field (a shadow's soft edge) is brighter and
  // greyer than the field, so it passed as white; it is saturated light mixed in.
  static void mergeBlurIntoUnknown(ScanLineRegions& out) {
    for (auto* lines : {&out.vertical, &out.horizontal})
      for (ScanLine& line : *lines) {
        auto& rs = line.regions;
        for (std::size_t k = 0; k < rs.size(); ++k) {
          if (rs[k].cls != RegionClass::Unknown) continue;
          for (std::size_t j = k + 1; j < rs.size() && rs[j].cls == RegionClass::White; ++j) rs[j].cls = RegionClass::Unknown;
          for (std::size_t j = k; j-- > 0 && rs[j].cls == RegionClass::White;) rs[j].cls = RegionClass::Unknown;
        }
      }
  }

  // Same-class neighbours merge; small gaps between field and white are split between them.
  void cleanup(std::vector<ScanLine>& lines, bool vertical) {
    for (ScanLine& line : lines) {
      auto& regs = line.regions;
      // White specks inside the field, much thinner than a line there (sunlit grass tips),
      // are field.
      for (std::size_t k = 1; k + 1 < regs.size(); ++k) {
        ScanRegion& r = regs[k];
        if (r.cls != RegionClass::White || regs[k - 1].cls != RegionClass::Field ||
            regs[k + 1].cls != RegionClass::Field)
          continue;
        if (r.to - r.from < kMinWhiteFraction * expectedSize(line, r, vertical)) r.cls = RegionClass::Field;
      }
      mergeSame(regs);
      bool changed = false;
      for (std::size_t k = 1; k + 1 < regs.size(); ++k) {
        ScanRegion& gap = regs[k];
        const RegionClass a = regs[k - 1].cls, b = regs[k + 1].cls;
        if (gap.cls != RegionClass::Other) continue;
        if (!((a == RegionClass::Field && b == RegionClass::White) || (a == RegionClass::White && b == RegionClass::Field)))
          continue;
        const int mid = (gap.from + gap.to) / 2;
        if (gap.to - gap.from > std::max(2.0, kGapFraction * expectedSize(line, gap, vertical))) continue;
        regs[k - 1].to = mid;
        regs[k + 1].from = mid;
        gap.from = gap.to = mid;  // emptied, removed below
        changed = true;
      }
      if (changed)
        regs.erase(std::remove_if(regs.begin(), regs.end(), [](const ScanRegion& r) { return r.to <= r.from; }),
                   regs.end());
    }
  }

  // The expected size of a field line along the scan line at a region.
  double expectedSize(const ScanLine& line, const ScanRegion& r, bool vertical) const {
    if (!vertical) return grid_.lineWidthPx[line.coord];
    return grid_.lineHeightPx[std::clamp((r.from + r.to) / 2, 0, grid_.height - 1)];
  }

  static void mergeSame(std::vector<ScanRegion>& regs) {
    if (regs.empty()) return;
    std::size_t w = 0;
    for (std::size_t k = 1; k < regs.size(); ++k) {
      ScanRegion& a = regs[w];
      const ScanRegion& b = regs[k];
      if (b.cls == a.cls && b.from == a.to) {
        // Length-weighted mean colour.
        const double la = a.to - a.from, lb = b.to - b.from, l = la + lb;
        const double y = (a.colour.y * la + b.colour.y * lb) / l;
        const double u = (a.u * la + b.u * lb) / l, v = (a.v * la + b.v * lb) / l;
        a.colour = toYhs(y, u, v);
        a.u = static_cast<std::uint8_t>(std::lround(u));
        a.v = static_cast<std::uint8_t>(std::lround(v));
        a.to = b.to;
      } else {
        regs[++w] = b;
      }
    }
    regs.resize(w + 1);
  }

 public:
  // The columns [left, right) of row y that lie below the boundary.
  static void cutRow(const FieldBoundary& boundary, int y, int& left, int& right) {
    int first = -1, last = -1;
    for (int x = left; x < right; x += 2)
      if (boundary.yAt(x + 0.5) <= y + 0.5) {
        if (first < 0) first = x;
        last = x;
      }
    if (first < 0) {
      right = left;
      return;
    }
    // Refine the ends to the pixel.
    while (first > left && boundary.yAt(first - 0.5) <= y + 0.5) --first;
    while (last + 1 < right && boundary.yAt(last + 1.5) <= y + 0.5) ++last;
    left = first;
    right = last + 1;
  }

 private:
  Pixels p_;
  const ScanGrid& grid_;
  const FieldBoundary* boundary_;
  std::vector<Sample> samples_;
  std::vector<std::size_t> lineSampleBegin_;
  std::vector<float> diffs_, chromaDiffs_;
  std::vector<int> cuts_;
  std::vector<RegionStats> stats_;  // vertical lines' regions, then horizontal lines'
  std::size_t verticalCount_ = 0;
  std::vector<char> hExtra_;  // per horizontal line of the output: an extra row
  std::vector<std::size_t> firstV_, firstH_;  // where each line's regions start in stats_
  std::vector<int> parent_;
  std::vector<SetSum> sets_;
  std::vector<char> isFieldSet_, member_;  // per set root; per region
  RegionStats fieldMean_{};
  float whiteU_ = 0, whiteV_ = 0;
  double edgeT_ = kMinEdge, chromaT_ = kMinChromaEdge, ratioMin_ = 0, fieldRatio_ = 0;
};

}  // namespace

ScanLineRegions computeScanLineRegions(const CameraImage& image, const ScanGrid& grid, const FieldBoundary* boundary) {
  if (!image.valid() || image.width != grid.width || image.height != grid.height) {
    ScanLineRegions out;
    out.camera = image.camera;
    return out;
  }
  Regionizer r(image, grid, boundary);
  return r.run(image.camera);
}

ScanLineRegions cutAtBoundary(const ScanLineRegions& regions, const FieldBoundary& boundary) {
  ScanLineRegions out;
  out.camera = regions.camera;
  out.fieldColour = regions.fieldColour;
  out.saturationLevel = regions.saturationLevel;
  if (!boundary.valid) {
    out.vertical = regions.vertical;
    out.horizontal = regions.horizontal;
    return out;
  }
  out.vertical.reserve(regions.vertical.size());
  for (const ScanLine& line : regions.vertical) {
    ScanLine cut;
    cut.coord = line.coord;
    cut.end = line.end;
    cut.start = std::clamp(static_cast<int>(std::ceil(boundary.yAt(line.coord + 0.5) - 0.5)), line.start, line.end);
    for (const ScanRegion& r : line.regions)
      if (r.to > cut.start) {
        cut.regions.push_back(r);
        // A white region the boundary cuts is mostly the world beyond (a wall in the light's
        // colour): not a line.
        if (r.from < cut.start && r.cls == RegionClass::White) cut.regions.back().cls = RegionClass::Other;
        cut.regions.back().from = std::max(r.from, cut.start);
      }
    out.vertical.push_back(std::move(cut));
  }
  for (const ScanLine& line : regions.horizontal) {
    int left = line.start, right = line.end;
    Regionizer::cutRow(boundary, line.coord, left, right);
    if (right - left < 2) continue;
    ScanLine cut;
    cut.coord = line.coord;
    cut.start = left;
    cut.end = right;
    for (const ScanRegion& r : line.regions)
      if (r.to > left && r.from < right) {
        cut.regions.push_back(r);
        if ((r.from < left || r.to > right) && r.cls == RegionClass::White) cut.regions.back().cls = RegionClass::Other;
        cut.regions.back().from = std::max(r.from, left);
        cut.regions.back().to = std::min(r.to, right);
      }
    out.horizontal.push_back(std::move(cut));
  }
  return out;
}

FieldSegmentation segmentField(const CameraImage& image, const CameraMatrix& cm, double lineWidthM) {
  FieldSegmentation s;
  s.grid = makeScanGrid(cm, image.width, image.height, lineWidthM);
  const ScanLineRegions all = computeScanLineRegions(image, s.grid, nullptr);
  s.boundary = detectFieldBoundary(image, all, cm);
  s.obstacles = detectObstacles(image, all, s.boundary, cm);
  s.regions = cutAtBoundary(all, s.boundary);
  return s;
}

}  // namespace nao
