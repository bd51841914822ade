#include "perception/RecordedCameraMatrix.h"

#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "robot/Error.h"
#include "robot/InputFiles.h"

namespace nao {
namespace {

using json = nlohmann::json;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

const json& member(const json& obj, const std::string& key, const std::string& path, const std::string& source) {
  if (!obj.is_object()) throw Error(source, path + ": must be an object");
  const auto it = obj.find(key);
  if (it == obj.end()) throw Error(source, (path.empty() ? key : path + "." + key) + ": missing");
  return *it;
}

// An array of n finite numbers.
std::vector<double> numbers(const json& v, std::size_t n, const std::string& path, const std::string& source) {
  if (!v.is_array() || v.size() != n)
    throw Error(source, path + ": must be an array of " + std::to_string(n) + " numbers");
  std::vector<double> out;
  for (std::size_t i = 0; i < n; ++i) {
    if (!v[i].is_number()) throw Error(source, path + "[" + std::to_string(i) + "]: must be a number");
    const double d = v[i].get<double>();
    if (!std::isfinite(d)) throw Error(source, path + "[" + std::to_string(i) + "]: must be finite");
    out.push_back(d);
  }
  return out;
}

Eigen::Isometry3d transform(const json& obj, const std::string& path, const std::string& source) {
  const std::vector<double> q = numbers(member(obj, "rotation", path, source), 4, path + ".rotation", source);
  const std::vector<double> t = numbers(member(obj, "translation", path, source), 3, path + ".translation", source);
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (std::abs(norm - 1) > 1e-3)
    throw Error(source, path + ".rotation: not a unit quaternion [x, y, z, w] (norm " + num(norm) + ")");
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(q[3], q[0], q[1], q[2]).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(t[0], t[1], t[2]);
  return T;
}

}  // namespace

CameraMatrix RecordedCameraMatrix::forImage(int width, int height) const {
  CameraMatrix cm = matrix;
  const double sx = static_cast<double>(width) / kWidth, sy = static_cast<double>(height) / kHeight;
  cm.intrinsics.width = width;
  cm.intrinsics.height = height;
  cm.intrinsics.fx *= sx;
  cm.intrinsics.cx *= sx;
  cm.intrinsics.fy *= sy;
  cm.intrinsics.cy *= sy;
  return cm;
}

const LabelledLine* RecordedCameraMatrix::line(const std::string& name) const {
  for (const auto& l : lines)
    if (l.name == name) return &l;
  return nullptr;
}

Eigen::Vector3d RecordedCameraMatrix::robotPoseOnField(const FieldDimensions& field, const std::string& source) const {
  struct GroundLine {
    Eigen::Vector2d p, d, mean;  // a point, the unit direction, the labelled points' middle
  };
  auto ground = [&](const char* name) {
    const LabelledLine* l = line(name);
    if (!l) throw Error(source, std::string("crossings: no ") + name + " (needed to place the robot)");
    const auto a = matrix.pixelToGround(l->a), b = matrix.pixelToGround(l->b);
    if (!a || !b) throw Error(source, std::string("crossings.") + name + ": a point at or above the horizon");
    return GroundLine{*a, (*b - *a).normalized(), (*a + *b) / 2};
  };
  const GroundLine goal = ground("border_line"), front = ground("goal_box_line"), side = ground("connecting_line");
  auto meet = [&](const GroundLine& g, const GroundLine& h) -> Eigen::Vector2d {
    const double det = g.d.x() * h.d.y() - g.d.y() * h.d.x();
    if (std::abs(det) < 0.2) throw Error(source, "crossings: the side line does not cross the goal-box lines");
    const Eigen::Vector2d r = h.p - g.p;
    return g.p + (r.x() * h.d.y() - r.y() * h.d.x()) / det * g.d;
  };
  const Eigen::Vector2d corner = meet(side, goal), frontCorner = meet(side, front);
  // Out of the goal along the side line, averaged with the normals of the two long lines.
  Eigen::Vector2d out = (frontCorner - corner).normalized();
  for (const GroundLine* g : {&goal, &front}) {
    Eigen::Vector2d n(-g->d.y(), g->d.x());
    out += n.dot(out) < 0 ? -n : n;
  }
  out.normalize();
  // Into the box: the way the front line runs on from its corner (its labelled points lie there).
  const Eigen::Vector2d inward = (front.mean - frontCorner).dot(front.d) >= 0 ? front.d : Eigen::Vector2d(-front.d);
  // Field: out = +x; inward = (0, -s) for the corner at y = s * width / 2.
  const double s = (out.x() * inward.y() - out.y() * inward.x()) > 0 ? -1 : 1;
  const double theta = -std::atan2(out.y(), out.x());
  const Eigen::Rotation2Dd R(theta);
  const Eigen::Vector2d cornerField(-field.length / 2, s * field.goalBoxAreaWidth / 2);
  const Eigen::Vector2d t = cornerField - R * corner;
  return {t.x(), t.y(), theta};
}

RecordedCameraMatrix RecordedCameraMatrix::parse(const std::string& text, const std::string& source) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::exception& e) {
    throw Error(source, std::string("invalid JSON: ") + e.what());
  }
  if (!root.is_object()) throw Error(source, "top level: must be an object");
  RecordedCameraMatrix r;
  const json& position = member(root, "position", "", source);
  if (position != "Top" && position != "Bottom") throw Error(source, "position: must be \"Top\" or \"Bottom\"");
  r.camera = position == "Top" ? CameraId::Top : CameraId::Bottom;

  const json& cm = member(root, "camera_matrix", "", source);
  r.matrix.pose = transform(member(cm, "camera_to_ground", "camera_matrix", source), "camera_matrix.camera_to_ground", source);
  const double height = r.matrix.pose.translation().z();
  if (!(height >= 0.05 && height <= 1.0))
    throw Error(source, "camera_matrix.camera_to_ground.translation[2]: the camera " + num(height) +
                            " m above the ground (0.05..1 m)");
  const std::vector<double> f = numbers(member(cm, "focal_length", "camera_matrix", source), 2, "camera_matrix.focal_length", source);
  const std::vector<double> c = numbers(member(cm, "optical_center", "camera_matrix", source), 2, "camera_matrix.optical_center", source);
  for (int i = 0; i < 2; ++i)
    if (!(f[i] >= 100 && f[i] <= 5000))
      throw Error(source, "camera_matrix.focal_length[" + std::to_string(i) + "]: " + num(f[i]) + " px (100..5000)");
  if (!(c[0] >= 0 && c[0] <= kWidth) || !(c[1] >= 0 && c[1] <= kHeight))
    throw Error(source, "camera_matrix.optical_center: (" + num(c[0]) + ", " + num(c[1]) + ") px is off the 640x480 image");
  r.matrix.intrinsics.width = kWidth;
  r.matrix.intrinsics.height = kHeight;
  r.matrix.intrinsics.fx = f[0];
  r.matrix.intrinsics.fy = f[1];
  r.matrix.intrinsics.cx = c[0];
  r.matrix.intrinsics.cy = c[1];

  if (const auto it = root.find("crossings"); it != root.end()) {
    if (!it->is_object()) throw Error(source, "crossings: must be an object");
    for (const char* name : {"border_line", "goal_box_line", "connecting_line"}) {
      const std::string k0 = std::string(name) + "_0", k1 = std::string(name) + "_1";
      const bool has0 = it->contains(k0), has1 = it->contains(k1);
      if (!has0 && !has1) continue;
      if (has0 != has1) throw Error(source, "crossings." + (has0 ? k1 : k0) + ": missing (a line needs both points)");
      LabelledLine l;
      l.name = name;
      const auto a = numbers((*it)[k0], 2, "crossings." + k0, source), b = numbers((*it)[k1], 2, "crossings." + k1, source);
      l.a = Eigen::Vector2d(a[0], a[1]);
      l.b = Eigen::Vector2d(b[0], b[1]);
      if ((l.a - l.b).norm() < 1) throw Error(source, "crossings." + k1 + ": the same point as " + k0);
      r.lines.push_back(l);
    }
  }
  return r;
}

RecordedCameraMatrix RecordedCameraMatrix::read(const std::string& path) {
  return parse(readInputFile(path), path);
}

}  // namespace nao
