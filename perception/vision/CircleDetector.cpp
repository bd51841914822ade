#include "perception/vision/CircleDetector.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace nao::vision {

double groundSigma(const CameraMatrix& cm, const Eigen::Vector2d& ground, double pixelSigma) {
  const double h = std::max(0.05, cm.pose.translation().z());
  const double d = (ground - cm.pose.translation().head<2>()).norm();
  return (h * h + d * d) / h * pixelSigma / cm.intrinsics.fy + 0.005;
}

namespace {

// Image distance of a spot from the projected ring (through the ring point nearest to it).
double ringResidualPx(const CameraMatrix& cm, const LineSpot& s, const Eigen::Vector2d& centre, double R) {
  const Eigen::Vector2d d = s.ground - centre;
  if (d.norm() < 1e-6) return 1e9;
  const auto p = cm.projectGround(centre + R * d.normalized());
  return p ? (*p - s.image).norm() : 1e9;
}

// Less than half the ring in view: its spots must bend in the image, i.e. the projected ring
// must explain them clearly better than a straight image line (a straight line's spots can
// lie within the ring's band for a while, and far away the ground range error hides the bend).
bool bendsInImage(const CameraMatrix& cm, const std::vector<LineSpot>& spots, const std::vector<int>& members,
                  const Eigen::Vector2d& centre, double R) {
  if (members.size() < 4) return false;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (int k : members) mean += spots[k].image;
  mean /= static_cast<double>(members.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (int k : members) cov += (spots[k].image - mean) * (spots[k].image - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
  const double lineRms = std::sqrt(std::max(0.0, es.eigenvalues()(0)) / members.size());
  double ring2 = 0;
  for (int k : members) ring2 += std::pow(ringResidualPx(cm, spots[k], centre, R), 2);
  const double ringRms = std::sqrt(ring2 / members.size());
  return lineRms > 1.5 && lineRms > 2 * ringRms;
}

struct Hypothesis {
  Eigen::Vector2d centre;
  int support = 0;
  int pieces = 1;
};

}  // namespace

Eigen::Vector2d fitCircleCentre(const std::vector<Eigen::Vector2d>& pts, const std::vector<double>& sigma,
                                Eigen::Vector2d c, double radius, int iterations) {
  for (int it = 0; it < iterations; ++it) {
    Eigen::Matrix2d jtj = Eigen::Matrix2d::Zero();
    Eigen::Vector2d jtr = Eigen::Vector2d::Zero();
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const Eigen::Vector2d d = pts[i] - c;
      const double n = d.norm();
      if (n < 1e-6) continue;
      const double w = 1 / (sigma[i] * sigma[i]);
      const Eigen::Vector2d j = -d / n;  // d(residual)/dc
      jtj += w * j * j.transpose();
      jtr += w * j * (n - radius);
    }
    if (std::abs(jtj.determinant()) < 1e-12) break;
    const Eigen::Vector2d step = -jtj.ldlt().solve(jtr);
    c += step;
    if (step.norm() < 1e-4) break;
  }
  return c;
}

bool looksLikeArc(const std::vector<Eigen::Vector2d>& pts, const std::vector<double>& sigma, double radius) {
  if (pts.size() < 4) return false;
  const Eigen::Vector2d a = pts.front(), b = pts.back();
  const double chord = (b - a).norm();
  if (chord < 1e-3 || chord > 2 * radius) return false;
  // Straight: total least squares.
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : pts) mean += p;
  mean /= static_cast<double>(pts.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : pts) cov += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
  const Eigen::Vector2d dir = es.eigenvectors().col(1);
  double chiLine = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Eigen::Vector2d r = pts[i] - mean;
    chiLine += std::pow((r.x() * dir.y() - r.y() * dir.x()) / sigma[i], 2);
  }
  // Arc: the better of the two sides.
  const Eigen::Vector2d mid = 0.5 * (a + b), u = (b - a) / chord, n(-u.y(), u.x());
  const double h = std::sqrt(std::max(0.0, radius * radius - 0.25 * chord * chord));
  double chiArc = 1e18;
  for (double side : {-1.0, 1.0}) {
    const Eigen::Vector2d c = fitCircleCentre(pts, sigma, mid + side * h * n, radius);
    double chi = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) chi += std::pow(((pts[i] - c).norm() - radius) / sigma[i], 2);
    chiArc = std::min(chiArc, chi);
  }
  const double n2 = static_cast<double>(pts.size());
  return chiLine / n2 > 1.5 && chiArc < 0.5 * chiLine;
}

LinesPercept::Circle detectCircle(const LineCandidates& candidates, const CameraImage& image,
                                  const FieldReference& field, const ObstaclesPercept& obstacles,
                                  const CameraMatrix& cm, const CircleParams& params, std::vector<char>* onCircle) {
  LinesPercept::Circle result;
  const auto& spots = candidates.spots;
  const double R = params.radius;
  if (onCircle) onCircle->assign(spots.size(), 0);
  std::vector<double> sigma(spots.size());
  for (std::size_t i = 0; i < spots.size(); ++i) sigma[i] = groundSigma(cm, spots[i].ground);

  // 1. Hypotheses from chains that bend like an arc of radius R.
  std::vector<Hypothesis> hyps;
  std::vector<Eigen::Vector2d> pts;
  std::vector<double> sig;
  for (const SpotChain& ch : candidates.chains) {
    if (ch.spots.size() < 4) continue;
    pts.clear(), sig.clear();
    for (int k : ch.spots) pts.push_back(spots[k].ground), sig.push_back(sigma[k]);
    const Eigen::Vector2d a = pts.front(), b = pts[pts.size() / 2], c = pts.back();
    const double chord = (c - a).norm();
    if (chord < 0.2 || chord > 2 * R + 0.2) continue;
    // Circumcentre of the ends and the middle gives the side the arc bends to.
    const double d = 2 * (a.x() * (b.y() - c.y()) + b.x() * (c.y() - a.y()) + c.x() * (a.y() - b.y()));
    if (std::abs(d) < 1e-9) continue;
    const double a2 = a.squaredNorm(), b2 = b.squaredNorm(), c2 = c.squaredNorm();
    const Eigen::Vector2d cc((a2 * (b.y() - c.y()) + b2 * (c.y() - a.y()) + c2 * (a.y() - b.y())) / d,
                             (a2 * (c.x() - b.x()) + b2 * (a.x() - c.x()) + c2 * (b.x() - a.x())) / d);
    const double r3 = (cc - a).norm();
    if (r3 < 0.5 * R || r3 > 2.5 * R) continue;
    const Eigen::Vector2d mid = 0.5 * (a + c), u = (c - a) / chord;
    Eigen::Vector2d n(-u.y(), u.x());
    if ((cc - mid).dot(n) < 0) n = -n;
    const double h = std::sqrt(std::max(0.0, R * R - 0.25 * chord * chord));
    Eigen::Vector2d centre = fitCircleCentre(pts, sig, mid + h * n, R);
    double chi = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const double r = ((pts[i] - centre).norm() - R) / sig[i];
      chi += r * r;
    }
    if (chi / pts.size() > 6.0) continue;
    bool merged = false;
    for (Hypothesis& hy : hyps)
      if ((hy.centre - centre).norm() < 0.3) {
        hy.centre = (hy.centre * hy.support + centre * pts.size()) / (hy.support + pts.size());
        hy.support += static_cast<int>(pts.size());
        merged = true;
        break;
      }
    if (!merged) hyps.push_back({centre, static_cast<int>(pts.size()), 1});
  }
  std::sort(hyps.begin(), hyps.end(), [](const Hypothesis& x, const Hypothesis& y) { return x.support > y.support; });
  if (hyps.size() > 4) hyps.resize(4);

  for (const Hypothesis& hy : hyps) {
    // 2. Refine over every spot on the ring.
    Eigen::Vector2d centre = hy.centre;
    std::vector<int> members;
    for (int it = 0; it < 3; ++it) {
      members.clear(), pts.clear(), sig.clear();
      for (std::size_t i = 0; i < spots.size(); ++i) {
        const double r = std::abs((spots[i].ground - centre).norm() - R);
        if (r > 2.5 * sigma[i] + 0.03) continue;
        // On the ground the range error grows with the square of the distance; in the image
        // the spot must lie on the ring's projection within a line's thickness there.
        if (ringResidualPx(cm, spots[i], centre, R) > 1.5 + 0.5 * spots[i].expectedPx) continue;
        members.push_back(static_cast<int>(i)), pts.push_back(spots[i].ground), sig.push_back(sigma[i]);
      }
      if (static_cast<int>(members.size()) < params.minSpots) break;
      centre = fitCircleCentre(pts, sig, centre, R);
    }
    if (static_cast<int>(members.size()) < params.minSpots) continue;
    std::array<char, 36> bins{};
    for (int k : members) {
      const Eigen::Vector2d d = spots[k].ground - centre;
      const int bin = static_cast<int>(std::floor((std::atan2(d.y(), d.x()) + M_PI) / (2 * M_PI) * 36)) % 36;
      bins[bin] = 1;
    }
    int covered = 0;
    for (char b : bins) covered += b;
    if (covered * 10 < params.minArcDeg) continue;
    // The spots must bend: a straight line along the ring passes the tests above.
    {
      std::vector<std::pair<double, int>> order;
      for (int k : members) {
        const Eigen::Vector2d d = spots[k].ground - centre;
        order.emplace_back(std::atan2(d.y(), d.x()), k);
      }
      std::sort(order.begin(), order.end());
      // Start after the largest angular gap, so the arc is in order.
      std::size_t start = 0;
      double gap = order.front().first + 2 * M_PI - order.back().first;
      for (std::size_t i = 1; i < order.size(); ++i)
        if (order[i].first - order[i - 1].first > gap) gap = order[i].first - order[i - 1].first, start = i;
      pts.clear(), sig.clear();
      for (std::size_t i = 0; i < order.size(); ++i) {
        const int k = order[(start + i) % order.size()].second;
        pts.push_back(spots[k].ground), sig.push_back(sigma[k]);
      }
      if (gap > M_PI && !bendsInImage(cm, spots, members, centre, R)) continue;
    }

    // 3. The white test along the ring where it is in view.
    int pairs = 0, passed = 0, samples = 0;
    constexpr int kSamples = 48;
    for (int k = 0; k < kSamples; ++k) {
      const double ang = 2 * M_PI * k / kSamples;
      const Eigen::Vector2d u(std::cos(ang), std::sin(ang));
      const auto p = cm.projectGround(centre + R * u);
      if (!p || !insideImage(image, p->x(), p->y(), 2) || obstacles.contains(p->x(), p->y())) continue;
      const auto pin = cm.projectGround(centre + (R - 0.5 * params.lineWidth) * u);
      const auto pout = cm.projectGround(centre + (R + 0.5 * params.lineWidth) * u);
      if (!pin || !pout) continue;
      const double widthPx = (*pout - *pin).norm();
      if (widthPx < 1e-6) continue;
      const Eigen::Vector2d n = (*pout - *pin) / widthPx;
      const double off = 0.5 * widthPx + std::max(2.0, 0.75 * widthPx);
      PixelColour sample = sampleColour(image, p->x(), p->y());
      if (widthPx < 4)
        for (double o : {-0.6, 0.6}) {
          const PixelColour c = sampleColour(image, p->x() + o * n.x(), p->y() + o * n.y());
          if (c.y > sample.y) sample = c;
        }
      ++samples;
      for (double side : {-1.0, 1.0}) {
        const Eigen::Vector2d q = *p + side * off * n;
        if (!insideImage(image, q.x(), q.y(), 1)) continue;
        const PixelColour comparison = sampleColour(image, q.x(), q.y());
        if (uninformative(comparison, field)) continue;
        ++pairs;
        passed += whitePair(sample, comparison, field);
      }
    }
    if (samples < params.minRingSamples || pairs == 0 || passed < params.whiteRatio * pairs) continue;
    result.found = true;
    result.centre = centre;
    result.radius = R;
    if (onCircle)
      for (int k : members) (*onCircle)[k] = 1;
    break;
  }
  return result;
}

}  // namespace nao::vision
