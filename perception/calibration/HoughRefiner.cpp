#include "perception/calibration/HoughRefiner.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Eigenvalues>
#include <opencv2/imgproc.hpp>

namespace nao::calibration {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

Eigen::Vector2d rotate(const Eigen::Vector2d& v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// The usable stretch of the coarse line: along-positions t in [0, length] outside the
// exclusions.
struct Stretch {
  Eigen::Vector2d a, d, n;  // origin (coarse from), unit direction, unit normal (d rotated +90 deg)
  double length = 0;
  std::vector<std::pair<double, double>> excluded;
  bool usable(double t) const {
    if (t < 0 || t > length) return false;
    for (const auto& [lo, hi] : excluded)
      if (t >= lo && t <= hi) return false;
    return true;
  }
  double usableLength() const {
    // Sampled: cheap and exact enough for a coverage ratio.
    int n = 0, in = 0;
    for (double t = 0; t <= length; t += 0.5, ++n) in += usable(t);
    return n ? length * in / n : 0;
  }
};

struct EdgeFit {
  bool ok = false;
  Eigen::Vector2d point, direction;  // on the line, unit
  ImageLine segment;                 // spanning the points used
  int points = 0;
  double rms = 0;
  double coverage = 0;
  double span = 0;  // the inliers' extent along the scan axis, of the scanned stretch's
};

// Does the edge at p, brighter towards nb, separate grass (its darker side) from paint?
// Always true without a greenness image.
bool grassToPaint(const GradientImage& g, const Eigen::Vector2d& p, const Eigen::Vector2d& nb, double inside,
                  const HoughRefinerOptions& o) {
  if (g.greenness.empty()) return true;
  auto at = [&](const Eigen::Vector2d& q) {
    const int x = std::clamp(static_cast<int>(std::floor(q.x())), 0, g.greenness.cols - 1);
    const int y = std::clamp(static_cast<int>(std::floor(q.y())), 0, g.greenness.rows - 1);
    return g.greenness.at<float>(y, x);
  };
  return at(p - o.colourOffsetPx * nb) - at(p + inside * nb) >= o.minGreennessStep;
}

// Total least squares through points (the principal axis), each point weighted by w (empty: 1).
void fitLine(const std::vector<Eigen::Vector2d>& pts, const std::vector<double>& w, Eigen::Vector2d& mean,
             Eigen::Vector2d& dir) {
  auto weight = [&](std::size_t i) { return w.empty() ? 1.0 : w[i]; };
  mean.setZero();
  double sum = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) mean += weight(i) * pts[i], sum += weight(i);
  mean /= sum;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (std::size_t i = 0; i < pts.size(); ++i) cov += weight(i) * (pts[i] - mean) * (pts[i] - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
  const Eigen::Vector2d d = es.eigenvectors().col(1);
  dir = d.dot(dir) < 0 ? Eigen::Vector2d(-d) : d;  // keep the orientation: the sides stay the sides
}

// Sub-pixel points of one edge near the Hough line {p : (p - a) . ne = rho}, polarity sign
// (+1: the gradient along ne is positive at the edge), then a robust line fit.
EdgeFit fitEdge(const GradientImage& g, const Stretch& st, const Eigen::Vector2d& ne, double rho, int sign,
                double inside, const HoughRefinerOptions& o) {
  EdgeFit fit;
  const int w = g.width(), h = g.height();
  const bool byColumn = std::abs(ne.y()) >= std::abs(ne.x());  // a flat line: scan columns
  auto across = [&](int x, int y) {
    return sign * (g.gx.at<float>(y, x) * ne.x() + g.gy.at<float>(y, x) * ne.y());
  };
  // The range of columns (rows) the stretch covers.
  const Eigen::Vector2d e0 = st.a, e1 = st.a + st.length * st.d;
  const double lo = byColumn ? std::min(e0.x(), e1.x()) : std::min(e0.y(), e1.y());
  const double hi = byColumn ? std::max(e0.x(), e1.x()) : std::max(e0.y(), e1.y());
  std::vector<Eigen::Vector2d> pts;
  std::vector<double> strength;
  int scanned = 0;
  double scannedLo = 1e30, scannedHi = -1e30;
  const int border = static_cast<int>(std::ceil(o.borderPx));
  for (int k = static_cast<int>(std::floor(lo)); k <= static_cast<int>(std::ceil(hi)); ++k) {
    const double c = k + 0.5;  // pixel centre coordinate along the scan axis
    // The Hough line's crossing of this column (row).
    Eigen::Vector2d p;
    if (byColumn) p = {c, st.a.y() + (rho - (c - st.a.x()) * ne.x()) / ne.y()};
    else p = {st.a.x() + (rho - (c - st.a.y()) * ne.y()) / ne.x(), c};
    if (!st.usable((p - st.a).dot(st.d))) continue;
    const int j0 = static_cast<int>(std::floor(byColumn ? p.y() : p.x()));
    const int limit = byColumn ? h : w;
    if (k < border || k >= (byColumn ? w : h) - border || j0 - 3 < border || j0 + 3 >= limit - border) continue;
    ++scanned;
    scannedLo = std::min(scannedLo, c);
    scannedHi = std::max(scannedHi, c);
    int best = j0;
    double bestV = -1e30;
    for (int j = j0 - 2; j <= j0 + 2; ++j) {
      const double v = byColumn ? across(k, j) : across(j, k);
      if (v > bestV) {
        bestV = v;
        best = j;
      }
    }
    if (bestV <= 0) continue;
    const double vm = byColumn ? across(k, best - 1) : across(best - 1, k);
    const double vp = byColumn ? across(k, best + 1) : across(best + 1, k);
    const double denom = vm - 2 * bestV + vp;
    if (!(denom < 0)) continue;  // not a peak
    const double off = std::clamp(0.5 * (vm - vp) / denom, -0.5, 0.5);
    const double at = best + 0.5 + off;
    const Eigen::Vector2d q = byColumn ? Eigen::Vector2d(c, at) : Eigen::Vector2d(at, c);
    if (!grassToPaint(g, q, sign * ne, inside, o)) continue;  // a shadow boundary, not the paint's edge
    pts.push_back(q);
    strength.push_back(bestV);
  }
  if (scanned == 0) return fit;
  // Weak peaks are noise or shadow, not the paint edge.
  const double minStrength = o.minStrengthRatio * median(strength);
  std::vector<Eigen::Vector2d> kept;
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (strength[i] >= minStrength) kept.push_back(pts[i]);
  // Start from the Hough line; then refit on the inliers twice.
  Eigen::Vector2d mean = st.a + rho * ne, dir(ne.y(), -ne.x());
  std::vector<Eigen::Vector2d> inliers;
  for (int round = 0; round < 3; ++round) {
    const Eigen::Vector2d nn(-dir.y(), dir.x());
    std::vector<double> res;
    for (const auto& q : kept) res.push_back(std::abs((q - mean).dot(nn)));
    const double sigma = 1.4826 * median(res);
    const double gate = round == 0 ? 1.5 : std::min(o.maxResidualPx, std::max(0.35, 3 * sigma));
    inliers.clear();
    for (std::size_t i = 0; i < kept.size(); ++i)
      if (res[i] <= gate) inliers.push_back(kept[i]);
    if (static_cast<int>(inliers.size()) < o.minPoints) return fit;
    fitLine(inliers, {}, mean, dir);
  }
  Eigen::Vector2d nn(-dir.y(), dir.x());
  double sum2 = 0, kMin = 1e30, kMax = -1e30;
  for (const auto& q : inliers) {
    const double k = byColumn ? q.x() : q.y();
    kMin = std::min(kMin, k);
    kMax = std::max(kMax, k);
    sum2 += std::pow((q - mean).dot(nn), 2);
  }
  // Wear only takes paint away, so of the inliers one that lies into the paint from the line is
  // more likely worn than one out of it: the final line counts the former paintSideWeight and
  // the latter 1 - paintSideWeight (an expectile, not the mean: it leans to the intact paint's
  // edge). Both edges lean outwards alike, so the line's centre stays; the inliers, their
  // scatter and coverage are the plain fit's.
  if (o.paintSideWeight != 0.5) {
    std::vector<double> weights(inliers.size());
    for (int round = 0; round < 20; ++round) {
      const double toPaint = nn.dot(sign * ne) > 0 ? 1 : -1;  // residuals > 0: into the paint
      for (std::size_t i = 0; i < inliers.size(); ++i)
        weights[i] = toPaint * (inliers[i] - mean).dot(nn) > 0 ? o.paintSideWeight : 1 - o.paintSideWeight;
      const Eigen::Vector2d lastMean = mean, lastDir = dir;
      fitLine(inliers, weights, mean, dir);
      nn = Eigen::Vector2d(-dir.y(), dir.x());
      if (std::abs((mean - lastMean).dot(nn)) < 1e-4 && std::abs(dir.x() * lastDir.y() - dir.y() * lastDir.x()) < 1e-7)
        break;
    }
  }
  double tMin = 1e30, tMax = -1e30;
  for (const auto& q : inliers) {
    const double t = (q - mean).dot(dir);
    tMin = std::min(tMin, t);
    tMax = std::max(tMax, t);
  }
  fit.ok = true;
  fit.point = mean;
  fit.direction = dir;
  fit.points = static_cast<int>(inliers.size());
  fit.rms = std::sqrt(sum2 / inliers.size());
  fit.segment = {mean + tMin * dir, mean + tMax * dir};
  // Coverage in scanned columns (rows): a steep stretch has fewer of them than its length.
  fit.coverage = static_cast<double>(inliers.size()) / scanned;
  fit.span = scannedHi > scannedLo ? (kMax - kMin) / (scannedHi - scannedLo) : 0.0;
  return fit;
}

}  // namespace

GradientImage GradientImage::sobel(const cv::Mat& gray) {
  cv::Mat f;
  if (gray.type() == CV_32F) f = gray;
  else gray.convertTo(f, CV_32F);
  GradientImage g;
  cv::Sobel(f, g.gx, CV_32F, 1, 0, 3, 1.0 / 8, 0, cv::BORDER_REPLICATE);
  cv::Sobel(f, g.gy, CV_32F, 0, 1, 3, 1.0 / 8, 0, cv::BORDER_REPLICATE);
  return g;
}

RefinedLine refineLine(const GradientImage& g, const ImageSegment& coarse, const std::vector<Exclusion>& exclusions,
                       const HoughRefinerOptions& o) {
  RefinedLine out;
  Stretch st;
  st.a = coarse.from;
  st.length = coarse.length();
  if (!(st.length > 4)) {
    out.reason = "too short to refine";
    return out;
  }
  st.d = coarse.direction();
  st.n = Eigen::Vector2d(-st.d.y(), st.d.x());
  for (const auto& e : exclusions) {
    const double t = (e.point - st.a).dot(st.d);
    st.excluded.emplace_back(t - e.radiusPx, t + e.radiusPx);
  }
  const double usable = st.usableLength();
  if (usable < 8) {
    out.reason = "too little of it away from junctions";
    return out;
  }

  // Hough accumulators over (angle offset, distance from the coarse origin), one per polarity.
  const double half = coarse.widthPx / 2 + o.bandMarginPx;
  const int nTheta = 2 * static_cast<int>(std::lround(o.angleRangeDeg / o.angleStepDeg)) + 1;
  const double rhoMax = half + st.length * std::sin(o.angleRangeDeg * kDeg) + 2;
  const int nRho = 2 * static_cast<int>(std::ceil(rhoMax / o.rhoStepPx)) + 2;
  std::vector<Eigen::Vector2d> normals(nTheta);
  for (int k = 0; k < nTheta; ++k) normals[k] = rotate(st.n, (k - nTheta / 2) * o.angleStepDeg * kDeg);
  std::vector<float> acc[2] = {std::vector<float>(nTheta * nRho, 0.f), std::vector<float>(nTheta * nRho, 0.f)};

  // Band pixels and their gradient across the coarse line.
  struct Vote {
    Eigen::Vector2d rel;
    float weight;
    int polarity;  // 0: positive along st.n, 1: negative
  };
  std::vector<Vote> votes;
  const Eigen::Vector2d corners[4] = {st.a + half * st.n, st.a - half * st.n, st.a + st.length * st.d + half * st.n,
                                      st.a + st.length * st.d - half * st.n};
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
  for (const auto& c : corners) {
    x0 = std::min(x0, c.x());
    x1 = std::max(x1, c.x());
    y0 = std::min(y0, c.y());
    y1 = std::max(y1, c.y());
  }
  const int b = static_cast<int>(std::ceil(o.borderPx));
  const int ix0 = std::max(b, static_cast<int>(std::floor(x0))), ix1 = std::min(g.width() - 1 - b, static_cast<int>(std::ceil(x1)));
  const int iy0 = std::max(b, static_cast<int>(std::floor(y0))), iy1 = std::min(g.height() - 1 - b, static_cast<int>(std::ceil(y1)));
  // Only the gradient maxima across the line vote, each at its sub-pixel position (parabola
  // through the maximum and its neighbours along the image axis nearest to the normal). Voting
  // with every pixel at its centre would let an axis-parallel Hough line collect whole pixel
  // rows and beat the true, slightly slanted edge.
  const double inside = std::clamp(coarse.widthPx / 2, 1.0, o.colourOffsetPx);
  const bool byColumn = std::abs(st.n.y()) >= std::abs(st.n.x());
  const int sx = byColumn ? 0 : 1, sy = byColumn ? 1 : 0;
  auto gnAt = [&](int x, int y) { return g.gx.at<float>(y, x) * st.n.x() + g.gy.at<float>(y, x) * st.n.y(); };
  std::vector<double> magnitudes;
  for (int y = std::max(iy0, 1); y <= std::min(iy1, g.height() - 2); ++y)
    for (int x = std::max(ix0, 1); x <= std::min(ix1, g.width() - 2); ++x) {
      const Eigen::Vector2d centre(x + 0.5, y + 0.5);
      const double t = (centre - st.a).dot(st.d), s = (centre - st.a).dot(st.n);
      if (std::abs(s) > half || !st.usable(t)) continue;
      const double gn = gnAt(x, y);
      const double gm = gnAt(x - sx, y - sy), gp = gnAt(x + sx, y + sy);
      const double sign = gn > 0 ? 1 : -1;
      if (sign * gn < sign * gm || sign * gn < sign * gp) continue;  // not a maximum across the edge
      const double denom = sign * (gm - 2 * gn + gp);
      const double off = denom < 0 ? std::clamp(0.5 * sign * (gm - gp) / denom, -0.5, 0.5) : 0.0;
      const Eigen::Vector2d p = centre + off * Eigen::Vector2d(sx, sy);
      if (!grassToPaint(g, p, sign * st.n, inside, o)) continue;
      votes.push_back({p - st.a, static_cast<float>(std::abs(gn)), gn > 0 ? 0 : 1});
      magnitudes.push_back(std::abs(gn));
    }
  if (votes.empty()) {
    out.reason = "no pixels to refine on";
    return out;
  }
  std::nth_element(magnitudes.begin(), magnitudes.begin() + magnitudes.size() * 95 / 100, magnitudes.end());
  const double threshold = 0.25 * magnitudes[magnitudes.size() * 95 / 100];
  for (const Vote& v : votes) {
    if (v.weight < threshold) continue;
    std::vector<float>& a = acc[v.polarity];
    for (int k = 0; k < nTheta; ++k) {
      const double f = (v.rel.dot(normals[k]) + rhoMax) / o.rhoStepPx;
      const int bin = static_cast<int>(std::floor(f));
      if (bin < 0 || bin + 1 >= nRho) continue;
      const float frac = static_cast<float>(f - bin);
      a[k * nRho + bin] += v.weight * (1 - frac);
      a[k * nRho + bin + 1] += v.weight * frac;
    }
  }

  // Each polarity's peak, interpolated between bins.
  EdgeFit fits[2];
  double rhos[2] = {0, 0};
  for (int p = 0; p < 2; ++p) {
    const std::vector<float>& a = acc[p];
    const auto it = std::max_element(a.begin(), a.end());
    if (*it <= 0) {
      out.reason = "no paint edge in the gradient image";
      return out;
    }
    const int idx = static_cast<int>(it - a.begin());
    const int kt = idx / nRho, kr = idx % nRho;
    auto parabola = [](double m, double c, double pl) {
      const double den = m - 2 * c + pl;
      return den < 0 ? std::clamp(0.5 * (m - pl) / den, -0.5, 0.5) : 0.0;
    };
    const double dr = (kr > 0 && kr + 1 < nRho) ? parabola(a[idx - 1], a[idx], a[idx + 1]) : 0.0;
    const double dt = (kt > 0 && kt + 1 < nTheta) ? parabola(a[idx - nRho], a[idx], a[idx + nRho]) : 0.0;
    const double angle = (kt + dt - nTheta / 2) * o.angleStepDeg * kDeg;
    const Eigen::Vector2d ne = rotate(st.n, angle);
    rhos[p] = (kr + dr) * o.rhoStepPx - rhoMax;
    fits[p] = fitEdge(g, st, ne, rhos[p], p == 0 ? 1 : -1, inside, o);
    if (!fits[p].ok) {
      out.reason = std::string("too few edge points on its ") + (p == 0 ? "first" : "second") + " edge (occluded?)";
      return out;
    }
  }
  // A bright line on a darker ground: dark-to-bright along n first, then bright-to-dark.
  if (!(rhos[0] < rhos[1])) {
    out.reason = "not a bright line between two edges";
    return out;
  }
  // The edges converge towards the vanishing point, but not by much.
  if (std::abs(fits[0].direction.dot(fits[1].direction)) < std::cos(2 * o.angleRangeDeg * kDeg)) {
    out.reason = "its two edges are not parallel";
    return out;
  }
  out.coverage = std::min(fits[0].coverage, fits[1].coverage);
  out.span = std::min(fits[0].span, fits[1].span);
  const bool spanned = out.span >= o.minSpan && out.coverage >= o.minCoverageSpanned;
  if (out.coverage < o.minCoverage && !spanned) {
    out.reason = "edges found along only " + std::to_string(static_cast<int>(std::lround(100 * out.coverage))) +
                 "% of it (occluded?)";
    return out;
  }
  out.ok = true;
  out.measurement.edgeA = fits[0].segment;
  out.measurement.edgeB = fits[1].segment;
  out.measurement.support = fits[0].points + fits[1].points;
  out.measurement.rmsPx = std::sqrt((fits[0].rms * fits[0].rms * fits[0].points + fits[1].rms * fits[1].rms * fits[1].points) /
                                    (fits[0].points + fits[1].points));
  return out;
}

}  // namespace nao::calibration
