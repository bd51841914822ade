#include "controllers/modules/OracleVision.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "controllers/modules/ModuleField.h"
#include "perception/vision/BallDetector.h"
#include "perception/vision/IntersectionDetector.h"
#include "robot/Error.h"
#include "robot/ModuleRegistry.h"

namespace nao::modules {

namespace {

NAO_DEBUG_CHANNEL(kOracleSkips, "oracle_skips", "images the oracle vision could not use, with the reason (no oracle view: not the simulator's fast percept mode; no camera matrix)");

constexpr double kBallRadius = 0.05;  // m

// How many false percepts an image has: Poisson with the given mean.
int falseCount(double mean, std::mt19937_64& rng) {
  if (mean <= 0) return 0;
  return std::poisson_distribution<int>(mean)(rng);
}

// Two standard normal draws, y before x (the order GCC gave the arguments of the
// constructor this replaced): one seed, the same percepts from every compiler.
Eigen::Vector2d gaussian2(std::normal_distribution<double>& gauss, std::mt19937_64& rng) {
  const double y = gauss(rng);
  return {gauss(rng), y};
}

// A random ground point the camera sees, within maxDistance (nullopt after a few misses: a
// camera looking up sees little ground).
std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>> randomGroundPixel(const CameraMatrix& cm, double maxDistance,
                                                                             std::mt19937_64& rng) {
  std::uniform_real_distribution<double> ux(0, cm.intrinsics.width), uy(0, cm.intrinsics.height);
  for (int attempt = 0; attempt < 8; ++attempt) {
    const double y = uy(rng);  // drawn before x, as GCC ordered the arguments this replaced
    const Eigen::Vector2d px(ux(rng), y);
    const auto g = cm.pixelToGround(px);
    if (g && g->norm() <= maxDistance) return std::make_pair(px, *g);
  }
  return std::nullopt;
}

}  // namespace

double OracleVision::rate(const std::vector<double>& table, const std::vector<double>& bins, double distance) {
  for (std::size_t i = 0; i < bins.size() && i < table.size(); ++i)
    if (distance <= bins[i]) return table[i];
  return 0;
}

std::string OracleVision::check(const Params& p) {
  for (std::size_t i = 1; i < p.distanceBins.size(); ++i)
    if (!(p.distanceBins[i] > p.distanceBins[i - 1])) return "distanceBins: must increase";
  const std::size_t n = p.distanceBins.size();
  const std::pair<const char*, const std::vector<double>*> tables[] = {{"ball.detection", &p.ball.detection},
                                                                      {"lines.detection", &p.lines.detection},
                                                                      {"lines.detectionShort", &p.lines.detectionShort},
                                                                      {"circle.detection", &p.circle.detection},
                                                                      {"penaltyMark.detection", &p.penaltyMark.detection}};
  for (const auto& [name, table] : tables)
    if (table->size() != n)
      return std::string(name) + ": has " + std::to_string(table->size()) + " entries, distanceBins " + std::to_string(n);
  if (p.lines.longLength < p.lines.minLength) return "lines.longLength: must not be below minLength";
  return {};
}

OracleVision::OracleVision(const ModuleContext& context)
    : params_(context.load<Params>(name())), circleRadius_(fieldFor(context).centerCircleDiameter / 2),
      rng_(context.seed * 0x9e3779b97f4a7c15ULL ^ std::hash<std::string>{}(context.headId) ^ 0x0cac1e5eedULL) {
  if (const std::string problem = check(params_); !problem.empty())
    throw Error(context.configDir.empty() ? std::string(name()) : parameterFile(context.configDir, name()), problem);
}

CameraPercepts OracleVision::perceive(const OracleView& view, const CameraMatrix& cm, const Params& p, double circleRadius,
                                      std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uni(0, 1);
  std::normal_distribution<double> gauss(0, 1);
  auto happens = [&](double probability) { return uni(rng) < probability; };
  CameraPercepts out;
  out.camera = CameraId::Top;
  out.cameraMatrix = cm;
  out.processed = true;
  const double maxDistance = p.distanceBins.empty() ? 0 : p.distanceBins.back();

  // Lines: each visible stretch detected by its length and distance, its ends moved across it.
  for (const OracleView::Line& l : view.lines) {
    if (l.length < p.lines.minLength) continue;
    const auto& table = l.length >= p.lines.longLength ? p.lines.detection : p.lines.detectionShort;
    if (!happens(rate(table, p.distanceBins, l.distance))) continue;
    const Eigen::Vector2d along = l.imageTo - l.imageFrom;
    if (along.norm() < 1e-9) continue;
    const Eigen::Vector2d across = Eigen::Vector2d(-along.y(), along.x()).normalized();
    const Eigen::Vector2d a = l.imageFrom + p.lines.sigmaPx * gauss(rng) * across;
    const Eigen::Vector2d b = l.imageTo + p.lines.sigmaPx * gauss(rng) * across;
    const auto ga = cm.pixelToGround(a), gb = cm.pixelToGround(b);
    if (!ga || !gb) continue;
    LinesPercept::Line line;
    line.imageFrom = a, line.imageTo = b, line.from = *ga, line.to = *gb;
    out.lines.push_back(line);
  }
  for (int k = falseCount(p.lines.falsePerImage, rng); k > 0; --k) {
    const auto start = randomGroundPixel(cm, std::min(maxDistance, 4.0), rng);
    if (!start) break;
    const double angle = 2 * M_PI * uni(rng), length = 0.3 + 0.7 * uni(rng);
    const Eigen::Vector2d end = start->second + length * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    const auto endPx = cm.projectGround(end);
    if (!endPx) continue;
    LinesPercept::Line line;
    line.imageFrom = start->first, line.imageTo = *endPx, line.from = start->second, line.to = end;
    out.lines.push_back(line);
  }
  // Intersections as the vision finds them: from the lines just seen.
  out.intersections = vision::detectIntersections(out.lines, cm, ObstaclesPercept{});

  // The centre circle and the penalty mark: a detection rate and a ground error.
  auto spot = [&](const std::optional<OracleView::Spot>& s, const Params::Spot& sp) -> std::optional<Eigen::Vector2d> {
    if (s && happens(rate(sp.detection, p.distanceBins, s->distance)))
      if (const auto g = cm.pixelToGround(s->image)) return *g + sp.sigma * gaussian2(gauss, rng);
    if (happens(sp.falsePerImage))
      if (const auto r = randomGroundPixel(cm, std::min(maxDistance, 3.0), rng)) return r->second;
    return std::nullopt;
  };
  if (const auto c = spot(view.circleCentre, p.circle)) {
    out.circle.found = true;
    out.circle.centre = *c;
    out.circle.radius = circleRadius;
  }
  if (const auto m = spot(view.penaltyMark, p.penaltyMark)) {
    out.penaltyMark = *m;
    if (const auto px = cm.projectGround(*m)) out.penaltyMarkImage = *px;
  }

  // The ball: the vision reports one, the nearest detected.
  const OracleView::Ball* best = nullptr;
  for (const OracleView::Ball& b : view.balls) {
    if (b.inImage < p.ball.minInImage || !happens(rate(p.ball.detection, p.distanceBins, b.distance))) continue;
    if (!best || b.distance < best->distance) best = &b;
  }
  Eigen::Vector2d ballPx;
  double radiusPx = 0;
  bool reported = false;
  if (best) {
    const double sigma = std::max(p.ball.minSigmaPx, p.ball.sigmaPerRadius * best->radiusPx);
    ballPx = best->image + sigma * gaussian2(gauss, rng);
    radiusPx = best->radiusPx;
    reported = true;
  } else if (happens(p.ball.falsePerImage)) {
    if (const auto r = randomGroundPixel(cm, std::min(maxDistance, 5.0), rng)) {
      ballPx = r->first;
      radiusPx = std::max(2.0, cm.intrinsics.fx * kBallRadius / std::max(0.1, r->second.norm()));
      reported = true;
    }
  }
  if (reported)
    if (const auto g = cm.pixelToGround(ballPx, kBallRadius)) {
      BallPercept& ball = out.ball;
      ball.seen = true;
      ball.image = ballPx;
      ball.radiusPx = radiusPx;
      ball.position = *g;
      ball.confidence = 1;
      ball.covariance = vision::ballCovariance(cm, ballPx, radiusPx, kBallRadius);  // as the vision states it
    }
  return out;
}

void OracleVision::update() {
  const CameraImage& image = in<CurrentImage>().image;
  const ImageCameraMatrix& m = in<ImageCameraMatrix>();
  CameraPercepts& out = this->out<CameraPercepts>();
  const char* problem = !image.oracle ? "no oracle view (not the simulator's fast percept mode)"
                        : !m.valid || m.camera != image.camera ? "no camera matrix for the image's time"
                                                               : nullptr;
  if (problem) {
    debug(kOracleSkips, [&] { return nlohmann::json{{"camera", cameraName(image.camera)}, {"reason", problem}}; });
    out = CameraPercepts{};
  } else {
    out = perceive(*image.oracle, m.matrix, params_, circleRadius_, rng_);
  }
  out.camera = image.camera;
  out.timestamp = image.timestamp;
}

NAO_REGISTER_MODULE(OracleVision);

}  // namespace nao::modules
