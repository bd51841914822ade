#include "scenarios/CameraAgreement.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

#include <Eigen/Eigenvalues>
#include <opencv2/imgproc.hpp>

#include "controllers/StandController.h"
#include "perception/CameraModel.h"
#include "perception/Geometry.h"
#include "robot/Paths.h"
#include "sim/CameraRenderer.h"
#include "sim/ImageIO.h"
#include "sim/Lighting.h"
#include "sim/World.h"

namespace nao::sim {
namespace {

constexpr double kDeg = M_PI / 180;

// A paint edge of a straight field line: the line's centre segment offset by half the line
// width to one side, extended by half the width at both ends (lines overlap at corners).
struct Edge {
  Eigen::Vector2d from, to, normal;  // normal points away from the paint
  int line = 0;
  int side = 0;
};

bool painted(const FieldModel& f, const Eigen::Vector2d& p) {
  const double hw = f.dims.lineWidth / 2;
  for (const auto& l : f.lines) {
    const Eigen::Vector2d d = (l.to - l.from).normalized();
    const Eigen::Vector2d q = p - l.from;
    const double t = q.dot(d), n = std::abs(q.x() * d.y() - q.y() * d.x());
    if (t >= -hw && t <= (l.to - l.from).norm() + hw && n <= hw) return true;
  }
  const double r = (p - f.centerCircleCenter).norm();
  if (std::abs(r - f.centerCircleRadius) <= hw + 0.01) return true;  // polygonal circle: keep a margin
  for (const auto& c : f.penaltyCrosses)
    if ((p - c).cwiseAbs().maxCoeff() <= f.dims.penaltyCrossSize / 2 + 0.01) return true;
  if ((p - f.centerMark).cwiseAbs().maxCoeff() <= f.dims.penaltyCrossSize / 2 + 0.01) return true;
  return false;
}

std::vector<Edge> paintEdges(const FieldModel& f) {
  std::vector<Edge> edges;
  const double hw = f.dims.lineWidth / 2;
  for (int i = 0; i < static_cast<int>(f.lines.size()); ++i) {
    const auto& l = f.lines[i];
    const Eigen::Vector2d d = (l.to - l.from).normalized(), n(-d.y(), d.x());
    for (int s : {-1, 1})
      edges.push_back({l.from - hw * d + s * hw * n, l.to + hw * d + s * hw * n, s * n, i, s});
  }
  return edges;
}

// Luminance (BT.601) as float, row 0 at the top.
cv::Mat luminance(const cv::Mat& rgb) {
  cv::Mat gray;
  cv::cvtColor(rgb, gray, cv::COLOR_RGB2GRAY);
  gray.convertTo(gray, CV_32F);
  return gray;
}

double sampleBilinear(const cv::Mat& img, double x, double y) {
  // Pixel (i, j) holds the value at (i + 0.5, j + 0.5).
  const double fx = x - 0.5, fy = y - 0.5;
  const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
  if (x0 < 0 || y0 < 0 || x0 + 1 >= img.cols || y0 + 1 >= img.rows) return NAN;
  const double ax = fx - x0, ay = fy - y0;
  const float* r0 = img.ptr<float>(y0);
  const float* r1 = img.ptr<float>(y0 + 1);
  return (1 - ay) * ((1 - ax) * r0[x0] + ax * r0[x0 + 1]) + ay * ((1 - ax) * r1[x0] + ax * r1[x0 + 1]);
}

// Where the luminance profile across an edge crosses halfway between paint and grass:
// t (px) along the image normal n from the predicted pixel p. nullopt when the profile is
// not a clean bright-to-dark step (occluded, off the image, too little contrast).
std::optional<double> locateEdge(const cv::Mat& y, const Eigen::Vector2d& p, const Eigen::Vector2d& n,
                                 double widthPx) {
  const double inside = -std::min(widthPx / 2, 3.0);
  const double bright = sampleBilinear(y, p.x() + inside * n.x(), p.y() + inside * n.y());
  const double dark = sampleBilinear(y, p.x() + 3.5 * n.x(), p.y() + 3.5 * n.y());
  if (!std::isfinite(bright) || !std::isfinite(dark) || bright - dark < 40) return std::nullopt;
  const double level = (bright + dark) / 2;
  double prevT = inside, prev = bright;
  for (double t = inside + 0.05; t <= 3.5 + 1e-9; t += 0.05) {
    const double v = sampleBilinear(y, p.x() + t * n.x(), p.y() + t * n.y());
    if (!std::isfinite(v)) return std::nullopt;
    if (v <= level) return prevT + (prev - level) / (prev - v) * (t - prevT);
    prevT = t;
    prev = v;
  }
  return std::nullopt;
}

// Total least squares line through points: (point on line, unit direction).
std::pair<Eigen::Vector2d, Eigen::Vector2d> fitLine(const std::vector<Eigen::Vector2d>& pts) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : pts) mean += p;
  mean /= pts.size();
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : pts) cov += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
  return {mean, es.eigenvectors().col(1)};
}

std::optional<Eigen::Vector2d> intersect(const std::pair<Eigen::Vector2d, Eigen::Vector2d>& a,
                                         const std::pair<Eigen::Vector2d, Eigen::Vector2d>& b) {
  const Eigen::Vector2d& d1 = a.second;
  const Eigen::Vector2d& d2 = b.second;
  const double det = d1.x() * (-d2.y()) - d1.y() * (-d2.x());
  // Edges meeting at a shallow angle in the image (a far corner seen edge-on) locate their
  // intersection poorly: a 0.1 px error across one edge moves it by 0.1 / sin(angle) along
  // the other. Such corners measure the measurement, not the model; skip them.
  if (std::abs(det) < std::sin(25 * kDeg)) return std::nullopt;
  const Eigen::Vector2d r = b.first - a.first;
  const double t = (r.x() * (-d2.y()) - r.y() * (-d2.x())) / det;
  return a.first + t * d1;
}

struct EdgeSample {
  Eigen::Vector2d field;     // point on the edge, field frame
  Eigen::Vector2d measured;  // its pixel located in the image
  double along = 0;          // position along the edge, m
};

// Chooses head angles that put `target` near the image centre of `camera` for a robot
// standing at `pose`, by a coarse search over the head's range with the nominal model.
std::pair<double, double> aimHead(const Eigen::Vector2d& target, const Eigen::Vector3d& pose, CameraId camera,
                                  const CameraIntrinsics& in) {
  const Eigen::Vector2d rel = fieldToRobot(target, pose);
  const double yaw = std::clamp(std::atan2(rel.y(), rel.x()), -110 * kDeg, 110 * kDeg);
  double best = 1e9, bestPitch = 0;
  JointArray joints = StandController::standPosture();
  joints[HeadYaw] = yaw;
  for (double pitch = -38 * kDeg; pitch <= 29 * kDeg; pitch += 0.5 * kDeg) {
    joints[HeadPitch] = pitch;
    const CameraMatrix cm = computeCameraMatrix(joints, Eigen::Vector2d::Zero(), camera, CameraCalibration{}, in);
    const auto px = cm.fieldToImage(target, pose);
    if (!px) continue;
    const double err = std::abs(px->y() - in.height / 2.0);
    if (err < best) {
      best = err;
      bestPitch = pitch;
    }
  }
  return {yaw, bestPitch};
}

}  // namespace

AgreementResult measureCameraAgreement(const AgreementOptions& options) {
  SceneSpec spec;
  spec.field = FieldDimensions::load(options.fieldFile.empty() ? dataPath("config/field_dimensions.json")
                                                               : options.fieldFile);
  World world(spec, options.seed);
  mjModel* m = world.model();
  mjData* d = world.data();
  // Hide the robot's own body: this is a test of the projection, and the bottom camera sees
  // the robot's feet on the lines it measures.
  for (int g = 0; g < m->ngeom; ++g) {
    const char* name = mj_id2name(m, mjOBJ_GEOM, g);
    const int body = m->geom_bodyid[g];
    const char* bodyName = mj_id2name(m, mjOBJ_BODY, body);
    if ((bodyName && std::string(bodyName).rfind("r0/", 0) == 0) || (name && std::string(name).rfind("r0/", 0) == 0))
      m->geom_rgba[4 * g + 3] = 0;
  }
  CameraRenderer renderer(m);
  const Lighting lighting = Lighting::parse("default", dataPath("config/lighting.json"));
  const FieldModel& field = world.field();
  const std::vector<Edge> edges = paintEdges(field);

  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> uni(0, 1);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * uni(rng); };

  AgreementResult result;
  for (int offsetSetting = 0; offsetSetting < 2; ++offsetSetting) {
    for (CameraId camera : {CameraId::Top, CameraId::Bottom}) {
      const CameraResolution res = world.cameraResolution(camera);
      const CameraIntrinsics in = CameraIntrinsics::fromFovY(res.width, res.height, world.cameraFovY());
      for (int trial = 0; trial < options.poses; ++trial) {
        // A random corner to look at, from a random distance and direction.
        const auto& target = field.intersections[rng() % field.intersections.size()].position;
        const double dist = camera == CameraId::Top ? uniform(0.8, 3.5) : uniform(0.3, 0.75);
        const double bearing = uniform(-M_PI, M_PI);
        Eigen::Vector3d pose(target.x() + dist * std::cos(bearing), target.y() + dist * std::sin(bearing), 0);
        pose.z() = normalizeAngle(bearing + M_PI + uniform(-50, 50) * kDeg);
        auto [yaw, pitch] = aimHead(target, pose, camera, in);
        yaw = std::clamp(yaw + uniform(-12, 12) * kDeg, -115 * kDeg, 115 * kDeg);
        pitch = std::clamp(pitch + uniform(-4, 4) * kDeg, -38 * kDeg, 29 * kDeg);

        CameraCalibration offsets;
        if (offsetSetting == 1) {
          std::array<double, 6> a{};
          for (double& v : a) v = uniform(-options.maxOffsetDeg, options.maxOffsetDeg) * kDeg;
          offsets = CameraCalibration::fromArray(a);
        }
        world.setMiscalibration(0, offsets);
        JointArray posture = StandController::standPosture();
        posture[HeadYaw] = yaw;
        posture[HeadPitch] = pitch;
        world.placeRobot(0, pose, posture);

        const cv::Mat rgb = renderer.renderRgb(m, d, world.cameraIndex(0, camera), res.width, res.height, lighting);
        const cv::Mat y = luminance(rgb);
        const std::size_t cornersBefore = result.corners.size();
        // The model sees what the robot program sees, plus the offsets it was told.
        const SensorFrame sensors = world.sensors(0);
        const CameraMatrix cm = computeCameraMatrix(sensors.joints.position, sensors.inertial.angle, camera,
                                                     options.modelIgnoresOffsets ? CameraCalibration{} : offsets, in);
        const Eigen::Vector3d robotPose = world.robotPose(0);
        ++result.trials;

        // Sample every paint edge at 1 cm; keep the samples where the edge really separates
        // paint from grass (not at corners, not across other marks) and that are resolvable.
        std::vector<std::vector<EdgeSample>> samples(edges.size());
        for (std::size_t e = 0; e < edges.size(); ++e) {
          const Edge& edge = edges[e];
          const Eigen::Vector2d dir = (edge.to - edge.from).normalized();
          const double len = (edge.to - edge.from).norm();
          for (double s = 0; s <= len; s += 0.01) {
            const Eigen::Vector2d p = edge.from + s * dir;
            bool clean = true;
            for (double t : {-0.03, 0.0, 0.03}) {
              const Eigen::Vector2d q = p + t * dir;
              if (!painted(field, q - 0.01 * edge.normal) || painted(field, q + 0.01 * edge.normal) ||
                  painted(field, q + 0.06 * edge.normal))
                clean = false;
            }
            if (!clean) continue;
            const Eigen::Vector3d rel3 = cm.fieldPose(robotPose).inverse() * Eigen::Vector3d(p.x(), p.y(), 0);
            if (rel3.x() > 6 || rel3.x() < 0.05) continue;
            const auto px = cm.fieldToImage(p, robotPose);
            const auto pxOut = cm.fieldToImage(Eigen::Vector2d(p + 0.01 * edge.normal), robotPose);
            const auto pxIn = cm.fieldToImage(Eigen::Vector2d(p - field.dims.lineWidth * edge.normal), robotPose);
            if (!px || !pxOut || !pxIn) continue;
            if (px->x() < 6 || px->y() < 6 || px->x() > res.width - 6 || px->y() > res.height - 6) continue;
            const double widthPx = (*pxIn - *px).norm();
            if (widthPx < 2.5) continue;
            const Eigen::Vector2d n = (*pxOut - *px).normalized();
            const auto t = locateEdge(y, *px, n, widthPx);
            if (!t) continue;
            result.edgeErrorsPx.push_back(*t);
            samples[e].push_back({p, *px + *t * n, s});
          }
        }

        // A ray from the true optical centre to a ground point must reach it (the line paint's
        // own 1 mm box aside): anything hit earlier occludes it.
        const Eigen::Vector3d eye = world.cameraPose(0, camera).translation();
        // The robot's own (hidden) body is skipped: the ray starts inside its head.
        auto visible = [&](const Eigen::Vector2d& ground) {
          const Eigen::Vector3d aim(ground.x(), ground.y(), 0.002);
          Eigen::Vector3d from = eye;
          for (int hop = 0; hop < 8; ++hop) {
            const Eigen::Vector3d dir = aim - from;
            mjtNum pnt[3] = {from.x(), from.y(), from.z()}, vec[3] = {dir.x(), dir.y(), dir.z()};
            int geom = -1;
            const mjtNum hit = mj_ray(m, d, pnt, vec, nullptr, 1, -1, &geom);
            if (hit < 0 || hit >= 0.999) return true;  // vec spans the whole way: hit is a fraction of it
            const char* body = mj_id2name(m, mjOBJ_BODY, m->geom_bodyid[geom]);
            if (!body || std::string(body).rfind("r0/", 0) != 0) return false;
            from += (hit + 1e-4) * dir;
          }
          return false;
        };
        // Corners: where two edges meet and exactly one or three of the four quadrants are paint.
        bool any = false;
        for (std::size_t a = 0; a < edges.size(); ++a)
          for (std::size_t b = a + 1; b < edges.size(); ++b) {
            const Edge &ea = edges[a], &eb = edges[b];
            if (ea.line == eb.line) continue;
            const Eigen::Vector2d da = (ea.to - ea.from).normalized(), db = (eb.to - eb.from).normalized();
            const double det = da.x() * db.y() - da.y() * db.x();
            if (std::abs(det) < 0.5) continue;
            const Eigen::Vector2d r = eb.from - ea.from;
            const double ta = (r.x() * db.y() - r.y() * db.x()) / det;
            const double tb = (r.x() * da.y() - r.y() * da.x()) / det;
            if (ta < -1e-9 || tb < -1e-9 || ta > (ea.to - ea.from).norm() + 1e-9 || tb > (eb.to - eb.from).norm() + 1e-9)
              continue;
            const Eigen::Vector2d c = ea.from + ta * da;
            int paintedQuadrants = 0;
            for (int sa : {-1, 1})
              for (int sb : {-1, 1}) paintedQuadrants += painted(field, c + 0.005 * (sa * ea.normal + sb * eb.normal));
            if (paintedQuadrants != 1 && paintedQuadrants != 3) continue;
            const auto predicted = cm.fieldToImage(c, robotPose);
            if (!predicted || !cm.isOnImage(*predicted) || predicted->x() < 10 || predicted->y() < 10 ||
                predicted->x() > res.width - 10 || predicted->y() > res.height - 10)
              continue;
            // Both lines must be resolved at the corner (>= 3 px wide in the image), else the
            // two corners of a thin far line blur into one.
            bool resolved = true;
            for (const Edge* e : {&ea, &eb}) {
              const auto across = cm.fieldToImage(Eigen::Vector2d(c - field.dims.lineWidth * e->normal), robotPose);
              resolved = resolved && across && (*across - *predicted).norm() >= 3;
            }
            if (!resolved) continue;
            // Nothing may stand between the camera and what is measured (a goal's net or post).
            if (!visible(c)) continue;
            // Fit each edge near the corner (within 0.4 m of it), rejecting outliers once.
            auto fitNear = [&](std::size_t e) -> std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>> {
              std::vector<Eigen::Vector2d> pts;
              for (const auto& sm : samples[e])
                if ((sm.field - c).norm() < 0.4 && visible(sm.field)) pts.push_back(sm.measured);
              if (pts.size() < 6) return std::nullopt;
              auto line = fitLine(pts);
              std::vector<Eigen::Vector2d> inliers;
              for (const auto& p : pts) {
                const Eigen::Vector2d q = p - line.first;
                if (std::abs(q.x() * line.second.y() - q.y() * line.second.x()) < 1.0) inliers.push_back(p);
              }
              if (inliers.size() < 6) return std::nullopt;
              double spread = 0;
              for (const auto& p : inliers) spread = std::max(spread, (p - inliers.front()).norm());
              if (spread < 8) return std::nullopt;
              return fitLine(inliers);
            };
            const auto la = fitNear(a), lb = fitNear(b);
            if (!la || !lb) continue;
            const auto measured = intersect(*la, *lb);
            if (!measured) continue;
            result.corners.push_back({trial, camera, offsetSetting == 1, *predicted, *measured,
                                      (*measured - *predicted).norm()});
            any = true;
          }
        result.trialsWithCorners += any;
        if (!options.imagesDir.empty()) {
          cv::Mat big;
          cv::resize(rgb, big, cv::Size(), 2, 2, cv::INTER_NEAREST);
          for (std::size_t k = cornersBefore; k < result.corners.size(); ++k) {
            const auto& c = result.corners[k];
            cv::circle(big, cv::Point2d(2 * c.predicted.x(), 2 * c.predicted.y()), 5, cv::Scalar(0, 255, 0), 1);
            cv::circle(big, cv::Point2d(2 * c.measured.x(), 2 * c.measured.y()), 2, cv::Scalar(255, 0, 0), -1);
          }
          char name[96];
          std::snprintf(name, sizeof name, "/agreement_%s_%s_%02d.png", options.imagesDir.empty() ? "" : cameraName(camera),
                        offsetSetting ? "offsets" : "nominal", trial);
          writePng(options.imagesDir + name, big);
        }
      }
    }
  }

  double sum2 = 0;
  for (const auto& c : result.corners) {
    sum2 += c.errorPx * c.errorPx;
    result.cornerMaxPx = std::max(result.cornerMaxPx, c.errorPx);
  }
  if (!result.corners.empty()) result.cornerRmsPx = std::sqrt(sum2 / result.corners.size());
  std::vector<double> absErr;
  double e2 = 0;
  for (double e : result.edgeErrorsPx) {
    absErr.push_back(std::abs(e));
    e2 += e * e;
  }
  if (!absErr.empty()) {
    std::nth_element(absErr.begin(), absErr.begin() + absErr.size() / 2, absErr.end());
    result.edgeMedianAbsPx = absErr[absErr.size() / 2];
    result.edgeRmsPx = std::sqrt(e2 / absErr.size());
  }
  return result;
}

}  // namespace nao::sim
