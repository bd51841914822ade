#include "sim/GroundTruth.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "sim/SceneBuilder.h"
#include "sim/World.h"

namespace nao::sim {

std::optional<Eigen::Vector2d> truePixel(const World& world, int robot, CameraId camera, const Eigen::Vector3d& pField) {
  const Eigen::Isometry3d cam = world.cameraPose(robot, camera);
  const Eigen::Vector3d p = cam.inverse() * pField;  // B-Human camera axes
  if (p.x() <= 1e-6) return std::nullopt;
  const CameraResolution res = world.cameraResolution(camera);
  const double f = (res.height / 2.0) / std::tan(world.cameraFovY() / 2);
  return Eigen::Vector2d(res.width / 2.0 - f * p.y() / p.x(), res.height / 2.0 - f * p.z() / p.x());
}

namespace {

// mj_ray's nearest hit where it lies on the segment pnt..pnt+vec (hit fraction <= 1), else -1
// or a hit beyond. mj_ray tries every visible geom, and a field has hundreds (the paint's
// pieces, the ball's patches); a geom whose bounding sphere misses the segment cannot hit it,
// so only the few near the segment are tried (an oracle game spent 12% of its wall time in
// mj_ray).
mjtNum segmentRay(const mjModel* m, const mjData* d, const mjtNum pnt[3], const mjtNum vec[3], int* geomid) {
  const double vv = vec[0] * vec[0] + vec[1] * vec[1] + vec[2] * vec[2];
  mjtNum best = -1;
  *geomid = -1;
  for (int i = 0; i < m->ngeom; ++i) {
    // mj_ray's rule: a transparent geom (or material) is not seen.
    const int mat = m->geom_matid[i];
    if ((mat < 0 ? m->geom_rgba[4 * i + 3] : m->mat_rgba[4 * mat + 3]) == 0) continue;
    const int type = m->geom_type[i];
    const mjtNum* size = m->geom_size + 3 * i;
    // A plane is hit only within its rectangle where it has one (the paint's pieces); rbound 0
    // means unbounded.
    const double r2 = type == mjGEOM_PLANE ? (size[0] > 0 && size[1] > 0 ? size[0] * size[0] + size[1] * size[1] : 0.0)
                                           : m->geom_rbound[i] * m->geom_rbound[i];
    if (type != mjGEOM_HFIELD && r2 > 0) {
      const mjtNum* c = d->geom_xpos + 3 * i;
      const double cx = c[0] - pnt[0], cy = c[1] - pnt[1], cz = c[2] - pnt[2];
      const double t = std::clamp((cx * vec[0] + cy * vec[1] + cz * vec[2]) / vv, 0.0, 1.0);
      const double dx = cx - t * vec[0], dy = cy - t * vec[1], dz = cz - t * vec[2];
      if (dx * dx + dy * dy + dz * dz > r2 * (1 + 1e-9) + 1e-12) continue;
    }
    const mjtNum hit = type == mjGEOM_MESH     ? mj_rayMesh(m, d, i, pnt, vec)
                       : type == mjGEOM_HFIELD ? mj_rayHfield(m, d, i, pnt, vec)
                                               : mju_rayGeom(d->geom_xpos + 3 * i, d->geom_xmat + 9 * i, size,
                                                             pnt, vec, type);
    if (hit >= 0 && (best < 0 || hit < best)) {
      best = hit;
      *geomid = i;
    }
  }
  return best;
}

}  // namespace

std::optional<SegmentHit> firstHit(const World& world, const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const Eigen::Vector3d dir = to - from;
  if (dir.norm() < 1e-12) return std::nullopt;
  const mjtNum pnt[3] = {from.x(), from.y(), from.z()}, vec[3] = {dir.x(), dir.y(), dir.z()};
  int geom = -1;
  const mjtNum hit = segmentRay(world.model(), world.data(), pnt, vec, &geom);
  if (hit < 0 || hit > 1) return std::nullopt;
  return SegmentHit{hit, geom};
}

namespace {

// allowBody: a body whose surface the point lies on (a ball), so hitting it means arriving.
bool visibleImpl(const World& world, int robot, CameraId camera, const Eigen::Vector3d& pField, double maxDistance,
                 const std::string& allowBody) {
  const auto px = truePixel(world, robot, camera, pField);
  const CameraResolution res = world.cameraResolution(camera);
  if (!px || px->x() < 0 || px->y() < 0 || px->x() >= res.width || px->y() >= res.height) return false;
  const Eigen::Vector3d eye = world.cameraPose(robot, camera).translation();
  if (std::hypot(pField.x() - eye.x(), pField.y() - eye.y()) > maxDistance) return false;
  // Cast a ray from the optical centre; the camera sits inside its own head, so the first
  // hits may be the robot's own geoms, which hide the point only when they are not the head.
  const mjModel* m = world.model();
  const std::string own = robotPrefix(robot);
  const std::string head = own + "Head";
  Eigen::Vector3d from = eye;
  for (int hop = 0; hop < 8; ++hop) {
    const auto h = firstHit(world, from, pField);
    if (!h || h->fraction >= 0.995) return true;
    const int geom = h->geom;
    const double hit = h->fraction;
    const Eigen::Vector3d dir = pField - from;
    const char* body = mj_id2name(m, mjOBJ_BODY, m->geom_bodyid[geom]);
    const char* name = mj_id2name(m, mjOBJ_GEOM, geom);
    const std::string geomName = name ? name : "";
    // The paint lies on the carpet, a ball point on the ball's own surface: not occluders.
    if (geomName.rfind("field/", 0) == 0) return true;
    if (body && !allowBody.empty() && std::string(body) == allowBody) return true;
    if (!body || std::string(body) != head) return false;
    from += (hit + 1e-4) * dir;
  }
  return false;
}

}  // namespace

bool trulyVisible(const World& world, int robot, CameraId camera, const Eigen::Vector3d& pField, double maxDistance) {
  return visibleImpl(world, robot, camera, pField, maxDistance, "");
}

std::optional<VisibleLine> visibleStretch(const World& world, int robot, CameraId camera, int index,
                                          double maxDistance, bool wholePaintWidth) {
  const FieldModel& field = world.field();
  const FieldLine& l = field.lines[index];
  const double len = (l.to - l.from).norm();
  if (len < 1e-9) return std::nullopt;
  const Eigen::Vector2d across = 0.5 * field.dims.lineWidth * Eigen::Vector2d(-(l.to - l.from).y(), (l.to - l.from).x()) / len;
  const CameraResolution res = world.cameraResolution(camera);
  auto inImage = [&](const Eigen::Vector2d& p) {
    const auto px = truePixel(world, robot, camera, Eigen::Vector3d(p.x(), p.y(), 0.001));
    return px && px->x() >= 0 && px->y() >= 0 && px->x() < res.width && px->y() < res.height;
  };
  const int n = std::max(2, static_cast<int>(len / 0.02) + 1);
  int bestStart = -1, bestLen = 0, runStart = -1;
  for (int k = 0; k <= n; ++k) {
    bool vis = false;
    if (k < n) {
      const Eigen::Vector2d p = l.from + (l.to - l.from) * (static_cast<double>(k) / (n - 1));
      vis = (!wholePaintWidth || (inImage(p + across) && inImage(p - across))) &&
            trulyVisible(world, robot, camera, Eigen::Vector3d(p.x(), p.y(), 0.001), maxDistance);
    }
    if (vis && runStart < 0) runStart = k;
    if (!vis && runStart >= 0) {
      if (k - runStart > bestLen) bestLen = k - runStart, bestStart = runStart;
      runStart = -1;
    }
  }
  if (bestLen < 2) return std::nullopt;
  VisibleLine v;
  v.index = index;
  v.name = l.name;
  v.from = l.from + (l.to - l.from) * (static_cast<double>(bestStart) / (n - 1));
  v.to = l.from + (l.to - l.from) * (static_cast<double>(bestStart + bestLen - 1) / (n - 1));
  v.visibleLength = (v.to - v.from).norm();
  v.imageFrom = *truePixel(world, robot, camera, Eigen::Vector3d(v.from.x(), v.from.y(), 0));
  v.imageTo = *truePixel(world, robot, camera, Eigen::Vector3d(v.to.x(), v.to.y(), 0));
  return v;
}

double discInImage(const Eigen::Vector2d& c, double r, int w, int h) {
  int in = 0, n = 0;
  for (int i = -4; i <= 4; ++i)
    for (int j = -4; j <= 4; ++j) {
      const Eigen::Vector2d p = c + r / 4 * Eigen::Vector2d(i, j);
      if ((p - c).norm() > r) continue;
      ++n;
      in += p.x() >= 0 && p.y() >= 0 && p.x() < w && p.y() < h;
    }
  return n ? double(in) / n : 0;
}

bool ballVisible(const World& world, int robot, CameraId camera, int ball, double maxDistance) {
  const Eigen::Vector3d centre = world.ballPosition(ball);
  const Eigen::Vector3d eye = world.cameraPose(robot, camera).translation();
  const std::string body = "ball" + std::to_string(ball);
  const Eigen::Vector3d towardCamera = centre + kBallRadius * (eye - centre).normalized();
  return visibleImpl(world, robot, camera, centre, maxDistance, body) ||
         visibleImpl(world, robot, camera, towardCamera, maxDistance, body);
}

VisibleFeatures visibleFeatures(const World& world, int robot, CameraId camera, double maxDistance) {
  VisibleFeatures out;
  const FieldModel& field = world.field();
  for (int i = 0; i < static_cast<int>(field.lines.size()); ++i)
    if (auto v = visibleStretch(world, robot, camera, i, maxDistance)) out.lines.push_back(std::move(*v));
  for (const auto& x : field.intersections) {
    const Eigen::Vector3d p(x.position.x(), x.position.y(), 0.001);
    if (trulyVisible(world, robot, camera, p, maxDistance))
      out.intersections.push_back({x, *truePixel(world, robot, camera, p)});
  }
  int circleVisible = 0;
  constexpr int kCircleSamples = 180;
  for (int k = 0; k < kCircleSamples; ++k) {
    const double a = 2 * M_PI * k / kCircleSamples;
    const Eigen::Vector2d p = field.centerCircleCenter + field.centerCircleRadius * Eigen::Vector2d(std::cos(a), std::sin(a));
    circleVisible += trulyVisible(world, robot, camera, Eigen::Vector3d(p.x(), p.y(), 0.001), maxDistance);
  }
  out.centreCircleFractionVisible = static_cast<double>(circleVisible) / kCircleSamples;
  for (const auto& c : field.penaltyCrosses)
    if (trulyVisible(world, robot, camera, Eigen::Vector3d(c.x(), c.y(), 0.001), maxDistance)) out.penaltyCross = c;
  const Eigen::Isometry3d cam = world.cameraPose(robot, camera);
  const CameraResolution res = world.cameraResolution(camera);
  const double f = (res.height / 2.0) / std::tan(world.cameraFovY() / 2);
  for (int b = 0; b < world.ballCount(); ++b) {
    const Eigen::Vector3d centre = world.ballPosition(b);
    if (!ballVisible(world, robot, camera, b, maxDistance)) continue;
    const auto px = truePixel(world, robot, camera, centre);
    if (!px) continue;
    VisibleBall v;
    v.index = b;
    v.position = centre;
    v.image = *px;
    v.distance = std::hypot(centre.x() - cam.translation().x(), centre.y() - cam.translation().y());
    v.radiusPx = f * kBallRadius / (cam.inverse() * centre).x();
    out.balls.push_back(v);
  }
  return out;
}

}  // namespace nao::sim
