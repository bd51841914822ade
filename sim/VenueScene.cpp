#include "sim/VenueScene.h"

#include <mujoco/mujoco.h>
#include <tinyxml2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "sim/Mjcf.h"

namespace nao::sim::venue {

namespace {

using mjcf::add;
using mjcf::num;
using mjcf::vec;
using mjcf::yawQuat;
using tinyxml2::XMLElement;

constexpr int kTurfTexels = 2048;    // along the carpet's length: about 5 mm per texel
constexpr int kPaintTexels = 256;    // per metre of paint (the texture repeats every metre)
constexpr double kTurfBase = 0.82;   // the texture's mean: room above it for the brighter patches
constexpr double kPieceLength = 0.5;  // m: a stroke's pieces
constexpr double kBendKnot = 3.0;     // m between the drift's values
constexpr double kBendTaper = 1.5;    // m over which a stroke's ends ease into the drift

double uniform(std::mt19937_64& g) { return static_cast<double>(g() >> 11) * 0x1.0p-53; }
double uniform(std::mt19937_64& g, double lo, double hi) { return lo + (hi - lo) * uniform(g); }
double gauss(std::mt19937_64& g) {
  const double u = std::max(uniform(g), 1e-300), v = uniform(g);
  return std::sqrt(-2 * std::log(u)) * std::cos(2 * std::numbers::pi * v);
}

std::uint64_t mix(std::uint64_t x) {  // splitmix64's finaliser
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

double smoothstep(double t) { return t * t * (3 - 2 * t); }  // 0..1 -> 0..1, flat at both ends

// Smooth value noise: lattice values uniform in +-sqrt(3) (sd 1), blended with smoothstep
// weights (the blend's sd is about 0.6). x, y in lattice units.

struct ValueNoise {
  std::uint64_t salt;
  double lattice(long i, long j) const {
    const std::uint64_t h = mix(salt ^ mix(static_cast<std::uint64_t>(i) * 0x632be59bd9b4e019ULL +
                                           static_cast<std::uint64_t>(j)));
    return (static_cast<double>(h >> 11) * 0x1.0p-53 * 2 - 1) * std::sqrt(3.0);
  }
  double at(double x, double y) const {
    const double fx = std::floor(x), fy = std::floor(y);
    const long i = static_cast<long>(fx), j = static_cast<long>(fy);
    const double tx = smoothstep(x - fx), ty = smoothstep(y - fy);
    const double a = lattice(i, j) + (lattice(i + 1, j) - lattice(i, j)) * tx;
    const double b = lattice(i, j + 1) + (lattice(i + 1, j + 1) - lattice(i, j + 1)) * tx;
    return a + (b - a) * ty;
  }
};

// A texture of `width` x `height` texels the compiler fills flat (paintTextures overwrites it).
void flatTexture(XMLElement* asset, const std::string& name, int width, int height) {
  add(asset, "texture",
      {{"name", name},
       {"type", "2d"},
       {"builtin", "flat"},
       {"rgb1", "1 1 1"},
       {"width", std::to_string(width)},
       {"height", std::to_string(height)}});
}

Eigen::Vector3d paintColour() { return {0.95, 0.95, 0.95}; }

int textureId(const mjModel* m, const char* name) { return mj_name2id(m, mjOBJ_TEXTURE, name); }

mjtByte byte(double v) { return static_cast<mjtByte>(std::clamp(v, 0.0, 1.0) * 255 + 0.5); }

// Where things stand around the carpet: on one of its four sides, `distance` beyond its edge,
// facing the field; kept apart from what was placed before.
struct Placer {
  const Hall& hall;
  std::mt19937_64& rng;
  std::vector<std::array<double, 3>> taken;  // x, y, radius

  // (x, y, yaw facing the field) or false when no free spot was found.
  bool place(double nearest, double farthest, double radius, Eigen::Vector3d& pose) {
    for (int attempt = 0; attempt < 400; ++attempt) {
      const double perimeter = 4 * (hall.carpetX + hall.carpetY);
      const double along = uniform(rng) * perimeter;
      const double d = uniform(rng, nearest, farthest);
      double x, y, yaw;
      if (along < 2 * hall.carpetX) {  // the long sides
        const bool left = along < hall.carpetX;
        x = (left ? along : along - hall.carpetX) * 2 - hall.carpetX;
        y = left ? hall.carpetY + d : -hall.carpetY - d;
        yaw = left ? -std::numbers::pi / 2 : std::numbers::pi / 2;
      } else {
        const double a = along - 2 * hall.carpetX;
        const bool opp = a < 2 * hall.carpetY;
        y = (opp ? a : a - 2 * hall.carpetY) - hall.carpetY;
        x = opp ? hall.carpetX + d : -hall.carpetX - d;
        yaw = opp ? std::numbers::pi : 0;
      }
      if (std::abs(x) > hall.wallX - radius || std::abs(y) > hall.wallY - radius) continue;
      bool free = true;
      for (const auto& [tx, ty, tr] : taken) free = free && std::hypot(x - tx, y - ty) > tr + radius;
      if (!free) continue;
      taken.push_back({x, y, radius});
      pose = {x, y, yaw + uniform(rng, -0.4, 0.4)};
      return true;
    }
    return false;
  }
};

void box(XMLElement* world, const std::string& name, const Eigen::Vector3d& centre, const Eigen::Vector3d& half,
         double yaw, const Eigen::Vector3d& rgba, const char* material = "scene_matte") {
  add(world, "geom",
      {{"name", name},
       {"type", "box"},
       {"material", material},
       {"rgba", vec({rgba.x(), rgba.y(), rgba.z(), 1})},
       {"pos", vec({centre.x(), centre.y(), centre.z()})},
       {"quat", yawQuat(yaw)},
       {"size", vec({half.x(), half.y(), half.z()})},
       {"contype", "0"},
       {"conaffinity", "0"},
       {"group", "1"}});
}

void capsule(XMLElement* world, const std::string& name, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
             double radius, const Eigen::Vector3d& rgba) {
  add(world, "geom",
      {{"name", name},
       {"type", "capsule"},
       {"material", "scene_matte"},
       {"rgba", vec({rgba.x(), rgba.y(), rgba.z(), 1})},
       {"fromto", vec({a.x(), a.y(), a.z(), b.x(), b.y(), b.z()})},
       {"size", num(radius)},
       {"contype", "0"},
       {"conaffinity", "0"},
       {"group", "1"}});
}

// A point `forward` ahead and `side` to the left of (x, y) facing yaw, at height z.
Eigen::Vector3d at(const Eigen::Vector3d& pose, double forward, double side, double z) {
  const double c = std::cos(pose.z()), s = std::sin(pose.z());
  return {pose.x() + c * forward - s * side, pose.y() + s * forward + c * side, z};
}

Eigen::Vector3d pick(std::mt19937_64& rng, std::initializer_list<Eigen::Vector3d> colours) {
  const auto k = static_cast<std::size_t>(uniform(rng) * static_cast<double>(colours.size()));
  return *(colours.begin() + std::min(k, colours.size() - 1));
}

void addPerson(XMLElement* world, const std::string& name, const Eigen::Vector3d& pose, std::mt19937_64& rng) {
  const double h = uniform(rng, 1.55, 1.92);
  const Eigen::Vector3d shirt = pick(rng, {{0.85, 0.1, 0.1}, {0.1, 0.2, 0.7}, {0.95, 0.95, 0.95}, {0.1, 0.1, 0.1},
                                           {0.95, 0.75, 0.1}, {0.2, 0.5, 0.25}, {0.5, 0.5, 0.55}, {0.9, 0.45, 0.1}});
  const Eigen::Vector3d trousers = pick(rng, {{0.1, 0.12, 0.25}, {0.08, 0.08, 0.08}, {0.55, 0.5, 0.4}, {0.3, 0.3, 0.32}});
  const Eigen::Vector3d skin = pick(rng, {{0.93, 0.76, 0.65}, {0.78, 0.57, 0.44}, {0.55, 0.38, 0.26}, {0.36, 0.24, 0.16}});
  const double hip = 0.48 * h, shoulder = 0.81 * h, stance = uniform(rng, 0.08, 0.14);
  for (const double side : {-1.0, 1.0}) {
    const std::string lr = side > 0 ? "l" : "r";
    capsule(world, name + "/leg_" + lr, at(pose, 0, side * stance, 0.06), at(pose, 0, side * 0.09, hip), 0.065, trousers);
    capsule(world, name + "/foot_" + lr, at(pose, -0.03, side * stance, 0.04), at(pose, 0.12, side * stance, 0.04), 0.04,
            {0.15, 0.15, 0.15});
    const double reach = uniform(rng, -0.15, 0.2);  // arms hang, or hold something in front
    capsule(world, name + "/arm_" + lr, at(pose, 0, side * 0.21, shoulder - 0.03),
            at(pose, reach, side * 0.23, 0.47 * h), 0.045, reach > 0.1 ? skin : shirt);
  }
  box(world, name + "/torso", at(pose, 0, 0, (hip + shoulder) / 2), {0.11, 0.19, (shoulder - hip) / 2 + 0.02},
      pose.z(), shirt);
  capsule(world, name + "/neck", at(pose, 0, 0, shoulder), at(pose, 0, 0, shoulder + 0.06), 0.05, skin);
  add(world, "geom",
      {{"name", name + "/head"},
       {"type", "ellipsoid"},
       {"material", "scene_matte"},
       {"rgba", vec({skin.x(), skin.y(), skin.z(), 1})},
       {"pos", vec({at(pose, 0, 0, 0).x(), at(pose, 0, 0, 0).y(), h - 0.11})},
       {"quat", yawQuat(pose.z())},
       {"size", "0.085 0.075 0.11"},
       {"contype", "0"},
       {"conaffinity", "0"},
       {"group", "1"}});
}

void addTable(XMLElement* world, const std::string& name, const Eigen::Vector3d& pose, std::mt19937_64& rng) {
  const double hx = uniform(rng, 0.3, 0.4), hy = uniform(rng, 0.6, 0.9), top = uniform(rng, 0.72, 0.76);
  const Eigen::Vector3d colour = pick(rng, {{0.85, 0.85, 0.82}, {0.55, 0.4, 0.25}, {0.3, 0.3, 0.3}});
  box(world, name + "/top", at(pose, 0, 0, top - 0.015), {hx, hy, 0.015}, pose.z(), colour);
  for (const double sx : {-1.0, 1.0})
    for (const double sy : {-1.0, 1.0})
      box(world, name + "/leg_" + std::to_string(static_cast<int>(sx + 1 + (sy + 1) / 2)),
          at(pose, sx * (hx - 0.04), sy * (hy - 0.04), (top - 0.03) / 2), {0.02, 0.02, (top - 0.03) / 2}, pose.z(),
          {0.2, 0.2, 0.2});
  const int laptops = 1 + static_cast<int>(uniform(rng) * 2);
  for (int k = 0; k < laptops; ++k) {
    const double side = (k - (laptops - 1) / 2.0) * 0.45;
    box(world, name + "/laptop" + std::to_string(k), at(pose, 0, side, top + 0.01), {0.12, 0.17, 0.01}, pose.z(),
        {0.12, 0.12, 0.13});
    box(world, name + "/screen" + std::to_string(k), at(pose, -0.12, side, top + 0.12), {0.005, 0.17, 0.11},
        pose.z(), {0.2, 0.25, 0.35});
  }
}

void addBoard(XMLElement* world, const std::string& name, const Eigen::Vector3d& pose, double halfLength,
              std::mt19937_64& rng) {
  const double h = uniform(rng, 0.5, 0.9);
  const int panels = 2 + static_cast<int>(uniform(rng) * 3);
  for (int k = 0; k < panels; ++k) {
    const double half = halfLength / panels;
    const double side = -halfLength + half * (2 * k + 1);
    const Eigen::Vector3d colour = pick(rng, {{0.9, 0.1, 0.1}, {0.1, 0.25, 0.8}, {0.95, 0.85, 0.1}, {0.95, 0.95, 0.95},
                                              {0.08, 0.08, 0.08}, {0.95, 0.5, 0.05}, {0.1, 0.6, 0.3}});
    box(world, name + "/panel" + std::to_string(k), at(pose, 0, side, h / 2), {0.02, half, h / 2}, pose.z(), colour);
    // A lettering band across the panel, in a contrasting colour.
    const Eigen::Vector3d ink = colour.mean() > 0.5 ? Eigen::Vector3d(0.05, 0.05, 0.08) : Eigen::Vector3d(0.95, 0.95, 0.95);
    box(world, name + "/text" + std::to_string(k), at(pose, 0.021, side, h * uniform(rng, 0.35, 0.65)),
        {0.002, half * 0.7, h * 0.1}, pose.z(), ink);
  }
}

}  // namespace

void addAssets(XMLElement* asset, const VenueLook& look) {
  flatTexture(asset, "scene_turf", kTurfTexels, kTurfTexels * 5 / 7);
  const Eigen::Vector3d turf = (look.turf / kTurfBase).cwiseMin(1.0);
  add(asset, "material",
      {{"name", "scene_turf"},
       {"texture", "scene_turf"},
       {"rgba", vec({turf.x(), turf.y(), turf.z(), 1})},
       {"texrepeat", "1 1"},
       {"texuniform", "false"},
       {"specular", num(look.sheen)},
       {"shininess", "0.05"},
       {"reflectance", "0"}});
  const Eigen::Vector3d paint = paintColour();
  for (int k = 0; k < kPaintMaterials; ++k) {
    const std::string name = "scene_paint" + std::to_string(k);
    flatTexture(asset, name, kPaintTexels, kPaintTexels);
    add(asset, "material",
        {{"name", name},
         {"texture", name},
         {"rgba", vec({paint.x(), paint.y(), paint.z(), 1})},
         {"texrepeat", "1 1"},
         {"texuniform", "true"},
         {"specular", "0"},
         {"shininess", "0"},
         {"reflectance", "0"}});
  }
  add(asset, "material", {{"name", "scene_matte"}, {"rgba", "1 1 1 1"}, {"specular", "0.05"}, {"reflectance", "0"}});
  add(asset, "material",
      {{"name", "scene_window"}, {"rgba", "0.85 0.9 1 1"}, {"emission", "0.9"}, {"specular", "0"}, {"reflectance", "0"}});
}

void piece(const PaintFn& paint, const std::string& name, const Eigen::Vector2d& centre, double halfLength,
           double width, double yaw, int layer, const VenueLook& look, std::mt19937_64& rng) {
  const double scale = std::clamp(1 + look.lineWidthJitter * gauss(rng), 0.75, 1.25);
  const int material = static_cast<int>(uniform(rng) * kPaintMaterials) % kPaintMaterials;
  paint(name, centre.x(), centre.y(), halfLength, width / 2 * scale, yaw, "scene_paint" + std::to_string(material), layer);
}

void stroke(const PaintFn& paint, const std::string& name, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
            double width, const VenueLook& look, std::mt19937_64& rng) {
  const double length = (to - from).norm();
  const Eigen::Vector2d dir = (to - from) / length, normal(-dir.y(), dir.x());
  const int n = std::max(1, static_cast<int>(std::lround(length / kPieceLength)));
  // The sideways drift: a slow wave (a value every kBendKnot m) that leaves both ends straight
  // and on the true line (where the stroke meets other lines, drawn with a square), easing in
  // over kBendTaper m. Its slope is at most 1.7 lineBend per metre from the wave plus 1 from the
  // easing: a line drawn along a string or tape drifts by millimetres over metres; it does not
  // kink by a degree next to a corner.
  const ValueNoise drift{rng()};
  auto ease = [](double u) { return smoothstep(std::clamp(u, 0.0, 1.0)); };
  auto offset = [&](double s) {
    const double taper = ease(s / kBendTaper) * ease((length - s) / kBendTaper);
    return look.lineBend * std::clamp(drift.at(s / kBendKnot, 0.5), -1.0, 1.0) * taper;
  };
  for (int k = 0; k < n; ++k) {
    const double s0 = length * k / n, s1 = length * (k + 1) / n;
    const Eigen::Vector2d a = from + dir * s0 + normal * offset(s0), b = from + dir * s1 + normal * offset(s1);
    piece(paint, name + "/" + std::to_string(k), (a + b) / 2, (b - a).norm() / 2, width,
          std::atan2(b.y() - a.y(), b.x() - a.x()), k % 2 ? 4 : 0, look, rng);
  }
}

void addHall(XMLElement* world, const VenueLook& look, const Hall& hall, std::uint64_t seed) {
  std::mt19937_64 rng(mix(seed ^ 0x76656e7565ULL));
  Placer placer{hall, rng, {}};
  // Windows and doors on the walls' inner faces.
  struct WallSide {
    double x, y, yaw, halfLength;
  };
  const std::array<WallSide, 4> walls = {WallSide{hall.wallX, 0, std::numbers::pi, hall.wallY},
                                         {-hall.wallX, 0, 0, hall.wallY},
                                         {0, hall.wallY, -std::numbers::pi / 2, hall.wallX},
                                         {0, -hall.wallY, std::numbers::pi / 2, hall.wallX}};
  std::vector<std::array<double, 3>> onWalls;  // wall, centre along, half width
  auto wallSpot = [&](double half, double& along) {
    for (int attempt = 0; attempt < 40; ++attempt) {
      const int w = static_cast<int>(uniform(rng) * 4) % 4;
      along = uniform(rng, -walls[w].halfLength + half + 0.2, walls[w].halfLength - half - 0.2);
      bool free = true;
      for (const auto& [ow, oa, oh] : onWalls) free = free && !(ow == w && std::abs(oa - along) < oh + half + 0.3);
      if (free) {
        onWalls.push_back({static_cast<double>(w), along, half});
        return w;
      }
    }
    return -1;
  };
  auto onWall = [&](int w, double along, double inset) {
    const WallSide& s = walls[w];
    const double c = std::cos(s.yaw), sn = std::sin(s.yaw);
    return Eigen::Vector2d(s.x + c * inset - sn * along, s.y + sn * inset + c * along);
  };
  for (int k = 0; k < look.windows; ++k) {
    const double half = uniform(rng, 0.6, 1.2), height = uniform(rng, 1.0, 1.4), bottom = uniform(rng, 0.8, 1.05);
    double along;
    const int w = wallSpot(half, along);
    if (w < 0) continue;
    const Eigen::Vector2d p = onWall(w, along, 0.005);
    box(world, "hall/window" + std::to_string(k), {p.x(), p.y(), bottom + height / 2}, {0.005, half, height / 2},
        walls[w].yaw, {0.85, 0.9, 1.0}, "scene_window");
  }
  for (int k = 0; k < look.doors; ++k) {
    const double half = uniform(rng, 0.45, 0.9);
    double along;
    const int w = wallSpot(half, along);
    if (w < 0) continue;
    const Eigen::Vector2d p = onWall(w, along, 0.01);
    const Eigen::Vector3d colour = pick(rng, {{0.35, 0.22, 0.12}, {0.2, 0.22, 0.25}, {0.75, 0.75, 0.72}, {0.15, 0.3, 0.55}});
    box(world, "hall/door" + std::to_string(k), {p.x(), p.y(), 1.05}, {0.01, half, 1.05}, walls[w].yaw, colour);
  }
  // A gym's floor lines: courts crossing the hall's margin, parallel to its walls.
  if (look.floorLines.maxCoeff() > 0) {
    const double z = hall.floorZ + 0.0005;
    int k = 0;
    for (const double side : {-1.0, 1.0}) {
      const double y = side * (hall.carpetY + uniform(rng, 0.4, 2.4));
      const double x = side * (hall.carpetX + uniform(rng, 0.4, 2.4));
      for (const auto& [cx, cy, hl, yaw] : {std::array<double, 4>{0, y, hall.wallX, 0},
                                             std::array<double, 4>{x, 0, hall.wallY, std::numbers::pi / 2}}) {
        add(world, "geom",
            {{"name", "hall/floor_line" + std::to_string(k++)},
             {"type", "plane"},
             {"material", "scene_matte"},
             {"rgba", vec({look.floorLines.x(), look.floorLines.y(), look.floorLines.z(), 1})},
             {"pos", vec({cx, cy, z})},
             {"quat", yawQuat(yaw)},
             {"size", vec({hl, 0.025, 1})},
             {"contype", "0"},
             {"conaffinity", "0"},
             {"group", "1"}});
      }
    }
  }
  for (int k = 0; k < look.boards; ++k) {
    const double half = uniform(rng, 0.75, 1.5);
    Eigen::Vector3d pose;
    if (!placer.place(0.3, 1.0, half, pose)) continue;
    pose.z() = std::round(pose.z() / (std::numbers::pi / 2)) * (std::numbers::pi / 2);  // along the carpet's edge
    addBoard(world, "hall/board" + std::to_string(k), pose, half, rng);
  }
  for (int k = 0; k < look.tables; ++k) {
    Eigen::Vector3d pose;
    if (placer.place(1.0, 2.4, 1.0, pose)) addTable(world, "hall/table" + std::to_string(k), pose, rng);
  }
  for (int k = 0; k < look.people; ++k) {
    Eigen::Vector3d pose;
    if (placer.place(0.3, 2.2, 0.35, pose)) addPerson(world, "hall/person" + std::to_string(k), pose, rng);
  }
}

void paintTextures(mjModel* m, const VenueLook& look, const Eigen::Vector2d& carpetSize, std::uint64_t seed) {
  std::mt19937_64 rng(mix(seed ^ 0x7475726eULL));
  // The carpet: brightness over patches (two scales), a hue drift per channel, stripes across
  // the length, a grain per texel. Slow parts on a coarse grid, bilinearly refined.
  const int turf = textureId(m, "scene_turf");
  if (turf >= 0) {
    const int w = m->tex_width[turf], h = m->tex_height[turf];
    mjtByte* rgb = m->tex_rgb + m->tex_adr[turf];
    const ValueNoise big{rng()}, small{rng()};
    const std::array<ValueNoise, 3> hue = {ValueNoise{rng()}, ValueNoise{rng()}, ValueNoise{rng()}};
    constexpr int kStep = 8;
    const int gw = w / kStep + 2, gh = h / kStep + 2;
    std::vector<std::array<double, 4>> coarse(static_cast<std::size_t>(gw * gh));
    for (int j = 0; j < gh; ++j)
      for (int i = 0; i < gw; ++i) {
        const double x = i * kStep * carpetSize.x() / w, y = j * kStep * carpetSize.y() / h;
        auto& c = coarse[static_cast<std::size_t>(j * gw + i)];
        c[0] = look.turfPatches * (1.3 * big.at(x / 1.2, y / 1.2) + 0.6 * small.at(x / 0.3, y / 0.3));
        for (int ch = 0; ch < 3; ++ch) c[1 + ch] = look.turfHue * 1.6 * hue[ch].at(x / 2.0, y / 2.0);
      }
    std::vector<double> stripe(static_cast<std::size_t>(w), 0.0);
    if (look.stripeWidth > 0)
      for (int i = 0; i < w; ++i) {
        const double x = (i + 0.5) * carpetSize.x() / w;
        stripe[static_cast<std::size_t>(i)] =
            look.stripeContrast * std::clamp(6 * std::sin(std::numbers::pi * x / look.stripeWidth), -1.0, 1.0);
      }
    std::uint64_t state = rng() | 1;
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        const int ci = i / kStep, cj = j / kStep;
        const double tx = static_cast<double>(i % kStep) / kStep, ty = static_cast<double>(j % kStep) / kStep;
        const auto& c00 = coarse[static_cast<std::size_t>(cj * gw + ci)];
        const auto& c10 = coarse[static_cast<std::size_t>(cj * gw + ci + 1)];
        const auto& c01 = coarse[static_cast<std::size_t>((cj + 1) * gw + ci)];
        const auto& c11 = coarse[static_cast<std::size_t>((cj + 1) * gw + ci + 1)];
        std::array<double, 4> v;
        for (int q = 0; q < 4; ++q)
          v[q] = (c00[q] * (1 - tx) + c10[q] * tx) * (1 - ty) + (c01[q] * (1 - tx) + c11[q] * tx) * ty;
        state ^= state << 13, state ^= state >> 7, state ^= state << 17;  // xorshift64: the grain
        const double g = (static_cast<double>(state >> 40) * 0x1.0p-24 + static_cast<double>((state >> 16) & 0xffffff) * 0x1.0p-24 - 1) * 2.45;
        const double brightness = kTurfBase * (1 + v[0] + stripe[static_cast<std::size_t>(i)] + look.grain * g);
        mjtByte* p = rgb + 3 * (static_cast<std::size_t>(j) * w + i);
        for (int ch = 0; ch < 3; ++ch) p[ch] = byte(brightness * (1 + v[1 + ch]));
      }
  }
  // The paint: worn spots down to the carpet (the share lineWear), and a faint unevenness.
  const Eigen::Vector3d worn = look.turf.cwiseQuotient(paintColour()).cwiseMin(1.0);
  for (int k = 0; k < kPaintMaterials; ++k) {
    const int id = textureId(m, ("scene_paint" + std::to_string(k)).c_str());
    if (id < 0) continue;
    const int w = m->tex_width[id], h = m->tex_height[id];
    mjtByte* rgb = m->tex_rgb + m->tex_adr[id];
    const ValueNoise fine{rng()}, coarse{rng()}, shade{rng()};
    std::vector<double> wear(static_cast<std::size_t>(w * h));
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        const double x = static_cast<double>(i) / w, y = static_cast<double>(j) / h;  // m (1 m per texture)
        wear[static_cast<std::size_t>(j * w + i)] = 0.5 * fine.at(x / 0.012, y / 0.012) + coarse.at(x / 0.06, y / 0.06);
      }
    std::vector<double> sorted = wear;
    const auto q = static_cast<std::size_t>((1 - look.lineWear) * static_cast<double>(sorted.size() - 1));
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(q), sorted.end());
    const double threshold = look.lineWear > 0 ? sorted[q] : 1e9;
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        const double x = static_cast<double>(i) / w, y = static_cast<double>(j) / h;
        const double t = std::clamp((wear[static_cast<std::size_t>(j * w + i)] - threshold) / 0.15, 0.0, 1.0) * 0.8;
        const double shading = 1 - 0.03 * std::abs(shade.at(x / 0.2, y / 0.2));
        mjtByte* p = rgb + 3 * (static_cast<std::size_t>(j) * w + i);
        for (int ch = 0; ch < 3; ++ch) p[ch] = byte(shading * (1 - t + t * worn[ch]));
      }
  }
}

}  // namespace nao::sim::venue
